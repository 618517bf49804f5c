#include "learn/motion/pc2_writer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <limits>
#include <numeric>
#include <random>

#include "core/io/input_error.h"
#include "core/io/text_file.h"
#include "core/scene/grid_builder.h"
#include "core/scene/mesh_node_order.h"
#include "core/scene/obj_mesh_builder.h"
#include "support/scene_test_support.h"

namespace neurocloth {
namespace {
using test::scratch_path;

std::int32_t int_at(const std::string& b, std::size_t at) {
  return static_cast<std::int32_t>(get_le32(reinterpret_cast<const unsigned char*>(&b[at])));
}

float float_at(const std::string& b, std::size_t at) {
  const std::uint32_t bits = get_le32(reinterpret_cast<const unsigned char*>(&b[at]));
  float v;
  std::memcpy(&v, &bits, 4);
  return v;
}

std::vector<Vec3> sample(int s) {
  return {Vec3(s, 0.5, -1), Vec3(0.1 * s, 2, 3e-3)};
}

// The layout Blender's Mesh Cache modifier reads (MOD_meshcache_pc2.cc), byte
// for byte: the header, then float32 x y z per point per sample.
TEST(Pc2Writer, WritesTheHeaderAndSamplesBlenderReads) {
  const std::string path = scratch_path("run.pc2");
  Pc2Writer w(path, 2);
  for (int s = 0; s < 3; ++s)
    w.add_frame(sample(s));
  w.finish();
  const std::string b = read_text_file(path, "pc2", 1 << 20);
  ASSERT_EQ(b.size(), 32u + 3 * 2 * 12);
  EXPECT_EQ(std::memcmp(b.data(), "POINTCACHE2\0", 12), 0);
  EXPECT_EQ(int_at(b, 12), 1);    // version
  EXPECT_EQ(int_at(b, 16), 2);    // points
  EXPECT_EQ(float_at(b, 20), 0);  // start frame
  EXPECT_EQ(float_at(b, 24), 1);  // sample rate: every frame
  EXPECT_EQ(int_at(b, 28), 3);    // samples
  // Sample 2, point 1.
  const std::size_t at = 32 + 2 * 24 + 12;
  EXPECT_EQ(float_at(b, at), 0.2f);
  EXPECT_EQ(float_at(b, at + 4), 2.0f);
  EXPECT_EQ(float_at(b, at + 8), 3e-3f);
}

TEST(Pc2Writer, RefusesWhatAFloatCannotHoldAndKeepsOnlyTheFramesAsked) {
  const std::string path = scratch_path("refuse.pc2");
  Pc2Writer w(path, 2);
  w.add_frame(sample(0));
  auto bad = sample(1);
  bad[1].z() = 1e39;  // finite as a double, infinite as a float
  EXPECT_THROW(w.add_frame(bad), std::runtime_error);
  bad[1].z() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(w.add_frame(bad), std::runtime_error);
  w.add_frame(sample(1));
  w.add_frame(sample(2));
  w.keep_first(2);
  w.finish();
  const std::string b = read_text_file(path, "pc2", 1 << 20);
  EXPECT_EQ(int_at(b, 28), 2);
  EXPECT_EQ(b.size(), 32u + 2 * 24);
  EXPECT_EQ(float_at(b, 32 + 24), 1.0f);
}

TEST(Pc2Writer, TheMeshGoesBesideTheCache) {
  EXPECT_EQ(pc2_mesh_path("out/run.pc2"), "out/run.obj");
  EXPECT_THROW(pc2_mesh_path("out/run.mdd"), InputError);
  EXPECT_THROW(pc2_mesh_path(".pc2"), InputError);
}

// A cloth whose nodes were renumbered at load: the OBJ written for the cache
// has the file's vertex order back, so point k of the cache is vertex k.
TEST(Pc2Writer, TheRestMeshIsInTheFilesVertexOrder) {
  GridSpec g;
  g.rows = 4;
  g.cols = 5;
  g.spacing = 0.1;
  const ClothTopology grid = build_grid(g);
  std::vector<std::int32_t> order(grid.rest_positions.size());
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(5));
  const ClothTopology shuffled = renumbered(grid, order);  // file order is the grid's
  ASSERT_FALSE(shuffled.numbering.identity());
  ObjMeshSpec spec;
  spec.path = scratch_path("rest.obj");
  write_rest_mesh_obj(shuffled, spec.path);
  const std::string text = read_text_file(spec.path, "obj", 1 << 20);
  std::size_t at = 0;
  for (std::size_t k = 0; k < grid.rest_positions.size(); ++k) {
    double x, y, z;
    ASSERT_EQ(std::sscanf(text.c_str() + at, "v %lf %lf %lf", &x, &y, &z), 3) << k;
    EXPECT_EQ(Vec3(x, y, z), grid.rest_positions[k]) << "vertex " << k;
    at = text.find('\n', at) + 1;
  }
  // The same triangles as the grid's, by file vertex.
  std::size_t faces = 0;
  for (std::size_t pos = text.find("\nf "); pos != std::string::npos;
       pos = text.find("\nf ", pos + 1))
    ++faces;
  EXPECT_EQ(faces, grid.triangles.size());
}

}  // namespace
}  // namespace neurocloth
