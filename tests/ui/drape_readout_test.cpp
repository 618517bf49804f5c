// The window's drape line (ui/drape_readout.h): what it says of a snapshot,
// that it measures again only for a newer snapshot and at most every
// kInterval, and that a scene without a support or a snapshot of another
// cloth shows nothing.
#include "ui/drape_readout.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "core/scene/scene.h"
#include "support/scene_builder.h"
#include "support/test_support.h"
#include "ui/scene_info.h"

namespace neurocloth::drape_readout_test {

Scene disc_on_a_post() {
  test::SceneBuilder b(2, 2, 0.1);
  b.disc(0.15, 6, Vec3(0, 0.202, 0))
      .module({{"type", "cylinder"}, {"center", {0, 0.1, 0}}, {"radius", 0.09}, {"height", 0.2}});
  return b.parse();
}

// The scene's cloth where it starts, as the simulation thread publishes it.
FrameSnapshot start_of(const Scene& scene, long serial) {
  FrameSnapshot s;
  for (const Vec3& p : scene.topology.rest_positions)
    for (int d = 0; d < 3; ++d)
      s.position.push_back(static_cast<float>(p[d]));
  s.serial = serial;
  return s;
}

TEST(DrapeReadout, SaysTheCoefficientAndNodesOfTheSnapshot) {
  const Scene scene = disc_on_a_post();
  SceneInfo info(scene);
  ASSERT_TRUE(info.drape().active());
  const FrameSnapshot flat = start_of(scene, 1);
  EXPECT_EQ(info.drape().line(flat, 0.0), "drape coefficient 1.000, 0 nodes over the cylinder");

  // The rim hung straight down: only the support's own shadow is left.
  FrameSnapshot hung = start_of(scene, 2);
  for (std::size_t i = 0; i < scene.topology.rest_positions.size(); ++i) {
    const Vec3 p = scene.topology.rest_positions[i];
    const double r = std::hypot(p.x(), p.z());
    if (r <= 0.09) continue;
    const double pull = 0.09 / r;
    hung.position[3 * i] = static_cast<float>(p.x() * pull);
    hung.position[3 * i + 1] = static_cast<float>(p.y() - (r - 0.09));
    hung.position[3 * i + 2] = static_cast<float>(p.z() * pull);
  }
  const std::string& line = info.drape().line(hung, 1.0);
  EXPECT_EQ(line.rfind("drape coefficient 0.0", 0), 0u) << line;
}

// A newer snapshot within kInterval of the last reading keeps the old line; the
// same snapshot later does too; a newer one after kInterval is measured.
TEST(DrapeReadout, MeasuresANewerSnapshotAtMostEveryInterval) {
  const Scene scene = disc_on_a_post();
  DrapeReadout readout(scene_drape_meter(scene));
  const FrameSnapshot first = start_of(scene, 1);
  readout.line(first, 10.0);
  EXPECT_EQ(readout.readings(), 1);
  readout.line(first, 20.0);
  EXPECT_EQ(readout.readings(), 1) << "the same snapshot again";
  const FrameSnapshot second = start_of(scene, 2);
  readout.line(second, 10.0 + 0.5 * DrapeReadout::kInterval);
  EXPECT_EQ(readout.readings(), 1) << "too soon";
  readout.line(second, 10.0 + DrapeReadout::kInterval);
  EXPECT_EQ(readout.readings(), 2);
}

TEST(DrapeReadout, ShowsNothingWithoutASupportOrForAnotherCloth) {
  SceneInfo hanging(test::asset_scene("hanging"));
  EXPECT_FALSE(hanging.drape().active());
  const Scene scene = disc_on_a_post();
  EXPECT_EQ(hanging.drape().line(start_of(scene, 1), 0.0), "");

  DrapeReadout readout(scene_drape_meter(scene));
  FrameSnapshot other = start_of(scene, 1);
  other.position.resize(other.position.size() - 3);  // a scene being replaced
  EXPECT_EQ(readout.line(other, 0.0), "");
  EXPECT_EQ(readout.readings(), 0);
}

}  // namespace neurocloth::drape_readout_test
