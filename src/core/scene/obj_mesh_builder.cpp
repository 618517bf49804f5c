#include "core/scene/obj_mesh_builder.h"

#include <limits>
#include <utility>

#include "core/io/obj_triangles.h"
#include "core/io/text_file.h"
#include "core/scene/triangle_springs.h"

namespace neurocloth {
namespace {

// As many nodes as the largest grid a scene may declare.
constexpr std::size_t kMaxVertices = 4'000'000;

}  // namespace

ClothTopology build_obj_mesh(const ObjMeshSpec& spec) {
  // A cloth has no limit of its own on triangles: its bytes bound them.
  const ObjLimits limits{kMaxMeshBytes, kMaxVertices, std::numeric_limits<std::size_t>::max()};
  ObjTriangles obj = read_obj_triangles(
      spec.path, limits, [&](const Vec3& v) -> Vec3 { return spec.scale * v + spec.translate; });
  ClothTopology t;
  t.rest_positions.reserve(obj.vertices.size());
  for (const Vec3& v : obj.vertices)
    t.rest_positions.push_back(spec.scale * v + spec.translate);
  t.triangles = std::move(obj.triangles);

  add_triangle_springs(t, spec.bend);
  return t;
}

}  // namespace neurocloth
