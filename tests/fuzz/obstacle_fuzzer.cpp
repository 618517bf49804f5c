// Fuzzes a mesh obstacle's reader, read_obstacle_mesh() (obj_triangles.cpp,
// point_cache_file.cpp and obstacle_mesh.cpp; tinyobjloader underneath). The
// bytes are a cache when they start as one would: a PC2 (its magic word), or
// an MDD (a big-endian frame count's high byte, 0), read with a fixed mesh,
// the point_cache seeds' square; else they are the obstacle's OBJ. Either way
// the obstacle is scaled, turned and moved. An accepted obstacle must hold
// finite vertices with finite norms, at least one triangle of three distinct
// existing vertices and one with an area, and, when it deforms, a frame of
// every vertex at each time, finite, the times finite and strictly increasing
// from 0.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/modules/obstacle_mesh.h"
#include "fuzz/fuzz_contract.h"
#include "fuzz/fuzz_input_file.h"

namespace neurocloth::fuzz {
namespace {

// The square at y = 1 that the point_cache seeds deform, as two triangles.
const char kSquare[] = "v 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\nf 1 2 3 4\n";

ObstacleFiles placement() {
  ObstacleFiles files;
  files.scale = 0.01;  // centimetres
  files.placement.rotation = euler_xyz_degrees(Vec3(30, 45, 60));
  files.placement.translation = Vec3(0.1, 0.2, 0.3);
  return files;
}

void check_vertices(const Contract& c, const std::vector<Vec3>& vertices, const std::string& what) {
  for (std::size_t i = 0; i < vertices.size(); ++i)
    if (!finite_norm(vertices[i])) c.vector(vertices[i], what + " vertex " + std::to_string(i));
}

// Per vertex, triangle and frame the checks test first and word a message
// only on a failure, so the harness stays cheap on large meshes.
void check_obstacle(const Contract& c, const ObstacleMesh& m) {
  const TriangleSurface& s = m.surface;
  const auto n = static_cast<std::int64_t>(s.vertices.size());
  check_vertices(c, s.vertices, "surface");
  c.require(!s.triangles.empty(), "an obstacle accepted with no triangles");
  bool area = false;
  for (const auto& t : s.triangles) {
    for (std::int32_t k : t)
      if (!(k >= 0 && k < n)) c.fail("a triangle names vertex " + std::to_string(k));
    c.require(t[0] != t[1] && t[1] != t[2] && t[0] != t[2],
              "a triangle accepted with a vertex twice");
    const Vec3 cross =
        (s.vertices[t[1]] - s.vertices[t[0]]).cross(s.vertices[t[2]] - s.vertices[t[0]]);
    area = area || cross.squaredNorm() > 0;
  }
  c.require(area, "an obstacle accepted with no triangle of any area");
  // What finish_surface derived (when it has), finite.
  for (std::size_t t = 0; t < s.face_normals.size(); ++t)
    if (!std::isfinite(s.face_normals[t].squaredNorm()))
      c.vector(s.face_normals[t], "face normal " + std::to_string(t));
  check_vertices(c, s.vertex_normals, "normal of");

  if (!m.deforms()) return;
  c.require(m.frame_times.size() == m.frames.size(), "as many times as frames");
  c.require(m.frame_times.front() == 0, "the first frame at " + show(m.frame_times.front()));
  for (std::size_t f = 0; f < m.frames.size(); ++f) {
    const std::string at = "frame " + std::to_string(f);
    c.finite(m.frame_times[f], at + " time");
    if (f > 0)
      c.require(m.frame_times[f] > m.frame_times[f - 1],
                at + " time " + show(m.frame_times[f]) + " after " + show(m.frame_times[f - 1]));
    c.require(m.frames[f].size() == s.vertices.size(), at + " without every vertex once");
    check_vertices(c, m.frames[f], at);
  }
}

}  // namespace
}  // namespace neurocloth::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace neurocloth;
  const bool pc2 = size >= 11 && std::memcmp(data, "POINTCACHE2", 11) == 0;
  const bool mdd = !pc2 && size >= 1 && data[0] == 0;
  ObstacleFiles files = fuzz::placement();
  if (pc2 || mdd) {
    static fuzz::InputFile square("square.obj");
    static const std::string& square_path = square.write(
        reinterpret_cast<const std::uint8_t*>(fuzz::kSquare), sizeof fuzz::kSquare - 1);
    static fuzz::InputFile pc2_file("input.pc2"), mdd_file("input.mdd");
    fuzz::InputFile& cache = pc2 ? pc2_file : mdd_file;
    files.obj = square_path;
    files.cache = cache.write(data, size);
    files.cache_fps = 24;  // a PC2's; an MDD has its times
    const auto mesh = fuzz::accepted("obstacle", [&] { return read_obstacle_mesh(files); });
    cache.remove();
    if (mesh) fuzz::check_obstacle(fuzz::Contract("obstacle"), **mesh);
    return 0;
  }
  if (fuzz::skip_known() && fuzz::long_line(data, size)) return 0;
  static fuzz::InputFile obj("input.obj");
  files.obj = obj.write(data, size);
  const auto mesh = fuzz::accepted("obstacle", [&] { return read_obstacle_mesh(files); });
  obj.remove();
  if (mesh) fuzz::check_obstacle(fuzz::Contract("obstacle"), **mesh);
  return 0;
}
