#include "core/modules/obstacle_mesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "core/io/input_error.h"
#include "core/io/obj_triangles.h"
#include "core/io/physical_limits.h"
#include "core/io/point_cache_file.h"
#include "core/io/text_file.h"

namespace neurocloth {
namespace {

constexpr ObjLimits kObstacleObjLimits{kMaxObstacleBytes, kMaxObstacleVertices,
                                       kMaxObstacleTriangles};
// A cache's coordinates are in the OBJ's units, before the scale: the OBJ's
// bound holds for them too. Its positions are bounded by its bytes.
constexpr PointCacheLimits kObstacleCacheLimits{kMaxObstacleCacheFrames, kMaxObstacleBytes / 12,
                                                kMaxObjCoordinate, "an obstacle's cache",
                                                "+-1e10 in any unit (before the mesh's scale)"};

// A triangle is flat when twice its area is below this fraction of its longest
// edge squared (the sine of its largest angle's supplement, roughly): corners
// on a line in exact arithmetic give a cross product of rounding only.
constexpr double kFlat = 1e-12;

bool has_area(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, bc = c - b;
  const double longest2 = std::max({ab.squaredNorm(), ac.squaredNorm(), bc.squaredNorm()});
  return ab.cross(ac).norm() > kFlat * longest2;
}

// Where the scene has a vertex of the files: scaled, then placed.
Vec3 placed(const ObstacleFiles& files, const Vec3& x) {
  return files.placement.apply(files.scale * x);
}

std::string shown_length(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.3g", v);
  return s;
}

// The OBJ's triangles, placed, refused when none has an area.
TriangleSurface placed_surface(const ObstacleFiles& files, ObjTriangles& obj) {
  TriangleSurface surface;
  surface.vertices.reserve(obj.vertices.size());
  for (const Vec3& v : obj.vertices)
    surface.vertices.push_back(placed(files, v));
  const std::vector<Vec3>& p = surface.vertices;
  const bool any = std::any_of(obj.triangles.begin(), obj.triangles.end(),
                               [&](const auto& t) { return has_area(p[t[0]], p[t[1]], p[t[2]]); });
  if (!any)
    throw InputError(files.obj, "f",
                     "every one of its " + std::to_string(obj.triangles.size()) +
                         " triangles (lines " + std::to_string(obj.lines.front()) + " to " +
                         std::to_string(obj.lines.back()) +
                         ") has zero area, its corners on a line or coinciding: no surface");
  surface.triangles = std::move(obj.triangles);
  return surface;
}

// The cache's frames, decoded, checked against the OBJ, turned Y-up if they
// are Z-up, and placed as the OBJ's vertices are.
void read_cache(const ObstacleFiles& files, const std::vector<Vec3>& obj_vertices,
                ObstacleMesh& mesh) {
  PointCacheFormat format = PointCacheFormat::pc2;
  if (!point_cache_format(files.cache, format))
    throw InputError(files.cache, "cache",
                     "not a point cache: the name must end in .pc2 or .mdd (a PC2 or an MDD, as "
                     "Blender exports them)");
  PointCacheClock clock;
  clock.mdd_from_first = true;
  if (format == PointCacheFormat::pc2) {
    if (!(files.cache_fps > 0))
      throw InputError(files.cache, "cache_fps",
                       "a PC2 cache holds no frame rate: give the mesh's \"cache_fps\" (frames "
                       "per second)");
    if (!limits::kFrameRate.contains(files.cache_fps))
      throw InputError(files.cache, "cache_fps", limits::kFrameRate.refusal(files.cache_fps));
    clock.fps = files.cache_fps;
  }
  PointCacheFrames cache =
      decode_point_cache(read_text_file(files.cache, "point cache", kMaxObstacleBytes), files.cache,
                         format, clock, kObstacleCacheLimits);
  check_cache_vertex_count(files.cache, cache.vertices(), files.obj, obj_vertices.size());

  double as_written = 0, turned = 0;
  const bool z_up = cache_is_z_up(cache.positions.front(), obj_vertices, as_written, turned);
  mesh.note =
      z_up ? "its cache turned from Z-up to Y-up, (x, y, z) -> (x, z, -y): its first frame is " +
                 shown_length(turned) + " (rms, the OBJ's units) from the OBJ so, " +
                 shown_length(as_written) + " as written"
           : "its cache read as written (Y-up): its first frame is " + shown_length(as_written) +
                 " (rms, the OBJ's units) from the OBJ, " + shown_length(turned) +
                 " turned from Z-up";
  for (std::vector<Vec3>& frame : cache.positions)
    for (Vec3& p : frame)
      p = placed(files, z_up ? z_up_to_y_up(p) : p);
  mesh.frame_times = std::move(cache.times);
  mesh.frames = std::move(cache.positions);
}

}  // namespace

std::shared_ptr<const ObstacleMesh> read_obstacle_mesh(const ObstacleFiles& files) {
  if (!(files.scale > 0) || !std::isfinite(files.scale) || !files.placement.rotation.allFinite() ||
      !files.placement.translation.allFinite())
    throw std::invalid_argument("read_obstacle_mesh: a scale or placement that is not finite");
  auto mesh = std::make_shared<ObstacleMesh>();
  mesh->obj_path = files.obj;
  mesh->cache_path = files.cache;
  // The shorter diagonal of a quad where the mesh will be.
  ObjTriangles obj = read_obj_triangles(files.obj, kObstacleObjLimits,
                                        [&](const Vec3& x) { return placed(files, x); });
  mesh->surface = placed_surface(files, obj);
  if (!files.cache.empty()) read_cache(files, obj.vertices, *mesh);
  finish_surface(mesh->surface);
  return mesh;
}

}  // namespace neurocloth
