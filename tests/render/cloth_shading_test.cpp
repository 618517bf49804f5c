// Normals and strain from a snapshot, against what a flat or uniformly
// stretched cloth must give.
#include "render/cloth_shading.h"

#include <gtest/gtest.h>

#include <cmath>

#include "support/render_test_support.h"

namespace neurocloth {
namespace {

using render_test::scene_snapshot;

TEST(ClothShading, AFlatClothHasUnitNormalsAlongTheVertical) {
  const FrameSnapshot s = scene_snapshot("hanging", 0);
  ClothShading shading;
  shading.update(s, false);
  ASSERT_EQ(shading.normal.size(), s.position.size());
  // The grid's triangles all wind the same way: every normal is the same unit vertical.
  const float sign = shading.normal[1] > 0 ? 1.0f : -1.0f;
  for (std::size_t i = 0; i < s.position.size() / 3; ++i) {
    EXPECT_NEAR(shading.normal[3 * i], 0, 1e-6) << i;
    EXPECT_NEAR(shading.normal[3 * i + 1], sign, 1e-6) << i;
    EXPECT_NEAR(shading.normal[3 * i + 2], 0, 1e-6) << i;
  }
}

TEST(ClothShading, NormalsFollowTheTrianglesWhenTheClothIsTurned) {
  FrameSnapshot s = scene_snapshot("hanging", 0);
  ClothShading flat;
  flat.update(s, false);
  // A quarter turn about x: (x, y, z) -> (x, -z, y) about y = 1.
  for (std::size_t i = 0; i < s.position.size() / 3; ++i) {
    const float y = s.position[3 * i + 1] - 1, z = s.position[3 * i + 2];
    s.position[3 * i + 1] = 1 - z;
    s.position[3 * i + 2] = y;
  }
  ClothShading turned;
  turned.update(s, false);
  for (std::size_t i = 0; i < s.position.size() / 3; ++i) {
    EXPECT_NEAR(turned.normal[3 * i + 1], -flat.normal[3 * i + 2], 1e-6);
    EXPECT_NEAR(turned.normal[3 * i + 2], flat.normal[3 * i + 1], 1e-6);
  }
}

TEST(ClothShading, StrainIsZeroAtRestAndTheStretchWhenScaledUniformly) {
  FrameSnapshot s = scene_snapshot("hanging", 0);
  ClothShading shading;
  shading.update(s, true);
  ASSERT_EQ(shading.strain.size(), s.position.size() / 3);
  for (const float e : shading.strain)
    EXPECT_NEAR(e, 0, 1e-6);
  for (float& x : s.position)
    x *= 1.07f;
  shading.update(s, true);
  for (const float e : shading.strain)
    EXPECT_NEAR(e, 0.07, 1e-5);
}

TEST(ClothShading, StrainIsHighestNearThePinsOfAHangingCloth) {
  const FrameSnapshot s = scene_snapshot("hanging", 1.0);
  ClothShading shading;
  shading.update(s, true);
  // hanging.json pins row 0's corners (nodes 0 and 19); they carry the cloth's weight.
  const float at_pins = (shading.strain[0] + shading.strain[19]) / 2;
  double mean = 0;
  for (const float e : shading.strain)
    mean += e;
  mean /= double(shading.strain.size());
  EXPECT_GT(at_pins, 3 * mean);
  EXPECT_GT(at_pins, 0.05);
}

TEST(ClothShading, ANodeInNoTriangleGetsAnUpwardNormal) {
  FrameSnapshot s = scene_snapshot("chain", 0);
  ClothShading shading;
  shading.update(s, true);
  for (std::size_t i = 0; i < s.position.size() / 3; ++i)
    EXPECT_EQ(shading.normal[3 * i + 1], 1.0f);
}

}  // namespace
}  // namespace neurocloth
