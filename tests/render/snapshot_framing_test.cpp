// The default snapshot camera shows the whole cloth and its colliders.
#include "render/snapshot_framing.h"

#include <gtest/gtest.h>

#include <limits>
#include <memory>

#include "support/render_test_support.h"
#include "support/triangle_meshes.h"

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

// hanging's cloth (x and z in [0, 0.95] at y = 1) with `colliders`,
// placed at time t.
FrameSnapshot hanging_with(std::vector<ModuleSpec> colliders, double t) {
  FrameSnapshot s = scene_snapshot("hanging", 0);
  auto g = std::make_shared<SceneGeometry>(*s.geometry);
  g->colliders = std::move(colliders);
  s.geometry = g;
  s.time = t;
  place_colliders(g.get(), t, s.colliders);
  return s;
}

// A box far below the cloth, moved by its keys, turned by its declaration;
// a mesh obstacle by its vertices, moved and deformed.
TEST(SnapshotFraming, BoundsHoldCollidersWhereTheSnapshotHasThem) {
  BoxSpec box;
  box.center = Vec3(0, -5, 0);
  box.half_extents = Vec3(1, 0.5, 0.5);
  box.motion.keys = {{0.0, Vec3::Zero(), Vec3::Zero()}, {1.0, Vec3(0, 0, 4), Vec3::Zero()}};
  Bounds b = snapshot_bounds(hanging_with({box}, 1.0));
  EXPECT_NEAR(b.lo.y(), -5.5, 1e-9);
  EXPECT_NEAR(b.hi.z(), 4.5, 1e-9);  // moved 4 m along z
  EXPECT_NEAR(b.lo.z(), 0.0, 1e-6);  // the cloth's, the box having left
  box.motion = {};
  box.rotate = Vec3(0, 90, 0);  // its long side now along z
  b = snapshot_bounds(hanging_with({box}, 0.0));
  EXPECT_NEAR(b.lo.z(), -1, 1e-9);
  EXPECT_NEAR(b.hi.z(), 1, 1e-9);
  EXPECT_NEAR(b.lo.x(), -0.5, 1e-9);

  auto mesh = std::make_shared<ObstacleMesh>();
  mesh->surface = test::icosphere(2, 0.5);
  for (Vec3& v : mesh->surface.vertices)
    v += Vec3(0, 3, 0);
  mesh->frame_times = {0.0, 1.0};
  mesh->frames = {mesh->surface.vertices, mesh->surface.vertices};
  for (Vec3& v : mesh->frames[1])
    v.y() *= 2;  // its top from 3.5 to 7 m
  MeshSpec spec;
  spec.mesh = mesh;
  spec.motion.keys = {{0.0, Vec3::Zero(), Vec3::Zero()}, {1.0, Vec3(-3, 0, 0), Vec3::Zero()}};
  b = snapshot_bounds(hanging_with({spec}, 0.0));
  EXPECT_NEAR(b.hi.y(), 3.5, 1e-9);
  b = snapshot_bounds(hanging_with({spec}, 1.0));
  EXPECT_NEAR(b.hi.y(), 7.0, 1e-5);  // the snapshot's float vertices
  EXPECT_NEAR(b.lo.x(), -3.5, 1e-5);
  // Planes stay out: they have no end.
  EXPECT_NEAR(snapshot_bounds(hanging_with({PlaneSpec{}}, 0.0)).lo.y(), 1.0, 1e-6);
}

}  // namespace
}  // namespace neurocloth
