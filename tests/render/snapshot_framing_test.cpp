// The default snapshot camera shows the whole cloth and its colliders.
#include "render/snapshot_framing.h"

#include <gtest/gtest.h>

#include <limits>

#include "support/render_test_support.h"

namespace neurocloth {
namespace {

using render_test::scene_snapshot;

TEST(SnapshotFraming, BoundsHoldTheClothAndTheFiniteColliders) {
  const FrameSnapshot s = scene_snapshot("table_drape", 0);
  const Bounds b = snapshot_bounds(s);
  // table_drape: the cloth spans x, z in [-0.6, 0.6] at y = 1; the table is
  // 0.8 x 0.75 x 0.8 standing on y = 0.
  EXPECT_NEAR(b.lo.x(), -0.6, 1e-3);
  EXPECT_NEAR(b.hi.z(), 0.6, 1e-3);
  EXPECT_NEAR(b.lo.y(), 0.0, 1e-9);
  EXPECT_NEAR(b.hi.y(), 1.0, 1e-6);
  EXPECT_TRUE(Bounds().empty());
}

TEST(SnapshotFraming, NonFiniteNodesAreLeftOut) {
  FrameSnapshot s = scene_snapshot("hanging", 0);
  s.position[3] = std::numeric_limits<float>::quiet_NaN();
  const Bounds b = snapshot_bounds(s);
  EXPECT_TRUE(b.lo.allFinite() && b.hi.allFinite());
}

TEST(SnapshotFraming, TheDefaultCameraShowsEveryNodeAndCollider) {
  for (const char* name : {"table_drape", "hanging", "sphere_drop", "flag", "chain"}) {
    const FrameSnapshot s = scene_snapshot(name, 0);
    for (const auto& [w, h] : {std::pair{1280, 720}, std::pair{400, 600}}) {
      const OrbitCamera c = framing_camera(s, double(w) / h);
      const Bounds b = snapshot_bounds(s);
      for (int k = 0; k < 8; ++k) {
        const Vec3 p((k & 1) ? b.hi.x() : b.lo.x(), (k & 2) ? b.hi.y() : b.lo.y(),
                     (k & 4) ? b.hi.z() : b.lo.z());
        double px, py;
        ASSERT_TRUE(c.project(p, w, h, px, py)) << name;
        EXPECT_TRUE(px >= 0 && px <= w && py >= 0 && py <= h) << name << " " << px << "," << py;
      }
    }
  }
}

}  // namespace
}  // namespace neurocloth
