// resized_grid: the same cloth on a finer or coarser grid keeps its width and
// its mass (per area, so a square keeps its total mass).
#include <gtest/gtest.h>

#include "core/scene/scene.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

// Distance between the first row's two corners: the cloth's width.
double width(const Scene& s) {
  const int cols = s.grid->cols;
  return (s.topology.rest_positions[cols - 1] - s.topology.rest_positions[0]).norm();
}

TEST(ResizedGrid, NumericMaterialKeepsTotalMassAndWidth) {
  const Scene hanging = test::asset_scene("hanging");  // 20 x 20 nodes of 10 g, 0.95 m wide
  for (int n : {16, 32, 64}) {
    const Scene s = resized_grid(hanging, n);
    EXPECT_NEAR(cloth_mass(s), 400 * 0.01, 1e-12) << n;
    EXPECT_NEAR(width(s), 19 * 0.05, 1e-12) << n;
    ASSERT_TRUE(s.resized_from);
    EXPECT_EQ(s.resized_from->rows, 20);
    EXPECT_NEAR(s.resized_from->mass, 4.0, 1e-12);
    // Springs keep their constants: a square sheet's stiffness per strain does
    // not depend on the spacing.
    EXPECT_EQ(s.material.spring_constant, hanging.material.spring_constant);
    EXPECT_EQ(s.material.viscosity, hanging.material.viscosity);
  }
}

TEST(ResizedGrid, MaterialInWordsKeepsTotalMassAndWidth) {
  const Scene drape = test::asset_scene("table_drape");  // 32 x 32, mass by area
  ASSERT_TRUE(drape.fuzzy_material);
  const double mass = cloth_mass(drape);
  for (int n : {16, 32, 64}) {
    const Scene s = resized_grid(drape, n);
    EXPECT_NEAR(cloth_mass(s), mass, 1e-12 * mass) << n;
    EXPECT_NEAR(width(s), width(drape), 1e-12) << n;
    EXPECT_EQ(s.material.node_mass, drape.material.node_mass);  // per area already
  }
}

TEST(ResizedGrid, ASquaredRectangleKeepsMassPerAreaAndAChainItsMass) {
  // The curtain, 32 x 24 nodes 5 cm apart, becomes square with its longer side:
  // 31/23 of its area, and as much more mass.
  const Scene curtain = test::asset_scene("curtain");
  const Scene square = resized_grid(curtain, 16);
  EXPECT_NEAR(cloth_mass(square), 768 * 0.004 * 31.0 / 23.0, 1e-12);
  EXPECT_NEAR(width(square), 31 * 0.05, 1e-12);
  // A chain (10 nodes of 20 g in a line) has no area to keep.
  EXPECT_NEAR(cloth_mass(resized_grid(test::asset_scene("chain"), 4)), 10 * 0.02, 1e-12);
}

}  // namespace
}  // namespace neurocloth
