#include "core/scene/obj_mesh_writer.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "core/scene/grid_builder.h"
#include "core/scene/obj_mesh_builder.h"
#include "support/scene_test_support.h"

namespace neurocloth {
namespace {
using test::scratch_path;

// The same nodes to the last bit or two (tinyobjloader's own decimal parser
// rounds less carefully than strtod), the same triangles exactly.
TEST(ObjMeshWriter, ReadsBackTheSameNodesAndTriangles) {
  GridSpec g;
  g.rows = 5;
  g.cols = 7;
  g.spacing = 0.0387;  // no short decimal: all 17 digits are needed
  g.origin = Vec3(-0.6, 1.0, -0.6);
  const ClothTopology grid = build_grid(g);
  ObjMeshSpec spec;
  spec.path = scratch_path("grid.obj");
  write_obj_mesh(grid, spec.path);
  const ClothTopology mesh = build_obj_mesh(spec);
  ASSERT_EQ(mesh.rest_positions.size(), grid.rest_positions.size());
  for (std::size_t i = 0; i < grid.rest_positions.size(); ++i)
    EXPECT_LT((mesh.rest_positions[i] - grid.rest_positions[i]).norm(), 1e-15) << "node " << i;
  EXPECT_EQ(mesh.triangles, grid.triangles);
}

TEST(ObjMeshWriter, NamesAFileItCannotWrite) {
  const std::string path = scratch_path("no/such/folder/grid.obj");
  try {
    write_obj_mesh(ClothTopology{}, path);
    FAIL() << "wrote " << path;
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace neurocloth
