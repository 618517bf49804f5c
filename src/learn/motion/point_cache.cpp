#include "learn/motion/point_cache.h"

#include <cmath>
#include <cstdio>
#include <numeric>
#include <utility>

#include "core/io/input_error.h"
#include "core/io/text_file.h"
#include "core/scene/obj_mesh_builder.h"
#include "learn/motion/cache_vertex_match.h"

namespace neurocloth {
namespace {

// What a reference may hold (reference_motion.h), in the decoder's words.
constexpr PointCacheLimits kReferenceCacheLimits{kMaxReferenceFrames, kMaxReferenceObservations,
                                                 kMaxReferenceCoordinate, "a reference",
                                                 "1e6 m from the origin (a unit mistake?)"};

std::string shown_value(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", v);
  return s;
}

// The decoded frames as a reference: vertex k is node k.
ReferenceMotion cache_motion(const std::string& path, PointCacheFrames&& cache) {
  ReferenceMotion m;
  m.path = path;
  m.source = ReferenceMotion::Source::cache;
  m.frames.resize(cache.times.size());
  for (std::size_t k = 0; k < m.frames.size(); ++k) {
    ReferenceFrame& frame = m.frames[k];
    frame.time = cache.times[k];
    frame.positions = std::move(cache.positions[k]);
    frame.nodes.resize(frame.positions.size());
    std::iota(frame.nodes.begin(), frame.nodes.end(), 0);
  }
  return m;
}

// The OBJ's vertices in its file order (build_obj_mesh renumbers its nodes).
std::vector<Vec3> obj_vertices(const std::string& path) {
  ObjMeshSpec spec;
  spec.path = path;
  spec.bend = false;
  const ClothTopology mesh = build_obj_mesh(spec);
  std::vector<Vec3> vertices(mesh.rest_positions.size());
  for (std::size_t k = 0; k < vertices.size(); ++k)
    vertices[k] = mesh.rest_positions[mesh.numbering.node(static_cast<int>(k))];
  return vertices;
}

}  // namespace

ReferenceMotion parse_pc2(const std::string& bytes, const std::string& path,
                          const ReferenceOptions& options) {
  PointCacheClock clock;
  clock.fps = required_fps(options, path, "a PC2 cache holds no frame rate");
  clock.start = checked_start(options, path);
  return cache_motion(path, decode_pc2(bytes, path, clock, kReferenceCacheLimits));
}

ReferenceMotion parse_mdd(const std::string& bytes, const std::string& path,
                          const ReferenceOptions& options) {
  PointCacheClock clock;
  clock.start = checked_start(options, path);
  clock.start_field = "--reference-start";
  ReferenceMotion m = cache_motion(path, decode_mdd(bytes, path, clock, kReferenceCacheLimits));
  // The file's times are what was simulated; a frame rate given beside them
  // that disagrees is said, not followed.
  const std::size_t frames = m.frames.size();
  if (options.fps > 0 && std::isfinite(options.fps) && frames > 1) {
    const double t0 = m.frames.front().time, span = m.frames.back().time - t0;
    bool agree = true;
    for (std::size_t k = 0; k < frames && agree; ++k)
      agree = std::abs(m.frames[k].time - t0 - static_cast<double>(k) / options.fps) <=
              0.01 / options.fps + 1e-6 * std::abs(m.frames[k].time);
    if (!agree)
      m.note = "its own times kept, not --reference-fps " + shown_value(options.fps) + " (its " +
               std::to_string(frames) + " frames span " + shown_value(span) + " s, " +
               shown_value(static_cast<double>(frames - 1) / span) + " frames per second)";
  }
  return m;
}

ReferenceMotion parse_point_cache(const std::string& bytes, const std::string& path,
                                  PointCacheFormat format, const std::vector<Vec3>& mesh,
                                  const std::string& mesh_path, std::size_t node_count,
                                  const ReferenceOptions& options) {
  ReferenceMotion m = format == PointCacheFormat::pc2 ? parse_pc2(bytes, path, options)
                                                      : parse_mdd(bytes, path, options);
  match_cache_to_scene(m, mesh, mesh_path, node_count, options.scene_positions);
  return m;
}

ReferenceMotion read_point_cache(const std::string& path, std::size_t node_count,
                                 const ReferenceOptions& options) {
  PointCacheFormat format = PointCacheFormat::pc2;
  if (!point_cache_format(path, format))
    throw InputError(path, "", "not a point cache: the name must end in .pc2 or .mdd");
  if (options.mesh.empty())
    throw InputError(path, "--reference-mesh",
                     "a point cache needs the mesh it deforms: give its OBJ (the cache's vertex k "
                     "is the mesh's vertex k)");
  const std::vector<Vec3> mesh = obj_vertices(options.mesh);
  return parse_point_cache(read_text_file(path, "point cache", kMaxReferenceBytes), path, format,
                           mesh, options.mesh, node_count, options);
}

}  // namespace neurocloth
