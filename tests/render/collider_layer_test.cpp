// Colliders drawn where the snapshot has them (collider_layer.h): a mesh
// obstacle as the solid it describes, a rotated box turned, a moving box at its
// pose for the frame, a deforming mesh at its vertices. Each is held to a
// frame of something already trusted drawn in the same place: the analytic
// box, a still box declared where the moving one has got to.
#include "render/collider_layer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <memory>

#include "core/modules/collider_motion.h"
#include "render/snapshot_framing.h"
#include "support/render_test_support.h"
#include "support/triangle_meshes.h"

namespace neurocloth {
namespace {

using namespace render_test;

constexpr int kW = 480, kH = 270;

// table_drape's flat cloth at its start with `colliders` instead of its table,
// at time t (placed as capture() places them).
FrameSnapshot with_colliders(std::vector<ModuleSpec> colliders, double t) {
  FrameSnapshot s = scene_snapshot("table_drape", 0);
  auto g = std::make_shared<SceneGeometry>(*s.geometry);
  g->colliders = std::move(colliders);
  s.geometry = g;
  s.time = t;
  place_colliders(g.get(), t, s.colliders);
  return s;
}

BoxSpec table() {
  BoxSpec box;
  box.center = Vec3(0, 0.375, 0);
  box.half_extents = Vec3(0.4, 0.375, 0.4);
  return box;
}

// The table as a mesh obstacle of 12 triangles.
MeshSpec table_mesh() {
  auto mesh = std::make_shared<ObstacleMesh>();
  mesh->surface = test::cube_surface(1.0);
  for (Vec3& v : mesh->surface.vertices)
    v = table().center + v.cwiseProduct(table().half_extents);
  MeshSpec spec;
  spec.mesh = mesh;
  return spec;
}

// Pixels with a channel more than `levels` apart.
int pixels_apart(const Image& a, const Image& b, int levels = 8) {
  EXPECT_EQ(a.rgba.size(), b.rgba.size());
  int n = 0;
  for (std::size_t i = 0; i + 3 < std::min(a.rgba.size(), b.rgba.size()); i += 4) {
    int worst = 0;
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(int(a.rgba[i + c]) - int(b.rgba[i + c])));
    n += worst > levels;
  }
  return n;
}

Image draw(const FrameSnapshot& s, const OrbitCamera& camera, bool grid = true) {
  RenderOptions o;
  o.grid = grid;
  return render_headless(s, camera, o, kW, kH);
}

// The camera of the table scene, for every frame compared.
OrbitCamera camera() {
  return framing_camera(with_colliders({table()}, 0), double(kW) / kH);
}

TEST(ColliderLayer, AMeshBoxIsDrawnAsTheBoxItDescribes) {
  const Image box = draw(with_colliders({table()}, 0), camera());
  const Image mesh = draw(with_colliders({table_mesh()}, 0), camera());
  const Image none = draw(with_colliders({}, 0), camera());
  // The table covers thousands of pixels; the two draw them alike (their
  // faces' diagonals differ, which flat faces do not show).
  EXPECT_GT(pixels_apart(box, none), 5000);
  EXPECT_LT(pixels_apart(box, mesh), 40);
}

TEST(ColliderLayer, AMovingBoxIsDrawnWhereItHasGot) {
  BoxSpec moving = table();
  moving.motion.keys = {{0.0, Vec3::Zero(), Vec3::Zero()}, {1.0, Vec3(0.5, 0, 0), Vec3::Zero()}};
  BoxSpec there = table();
  there.center += Vec3(0.5, 0, 0);
  // Without the grid: a moving collider is drawn after it, a still one before,
  // so where the table stands on the floor the grid's lines cross the still
  // one's foot and not the moving one's (docs/rendering.md).
  const Image at_start = draw(with_colliders({moving}, 0), camera(), false);
  const Image at_end = draw(with_colliders({moving}, 1), camera(), false);
  EXPECT_LT(pixels_apart(at_start, draw(with_colliders({table()}, 0), camera(), false)), 40);
  EXPECT_LT(pixels_apart(at_end, draw(with_colliders({there}, 0), camera(), false)), 40);
  EXPECT_GT(pixels_apart(at_start, at_end), 2000);
  EXPECT_LT(pixels_apart(draw(with_colliders({moving}, 1), camera()),
                         draw(with_colliders({there}, 0), camera())),
            200);
}

// A box turned by its declaration (drawn once, still) and one turned by its
// motion (placed every frame) look the same, and not like the unturned box.
TEST(ColliderLayer, ARotatedBoxIsTurnedStillOrMoving) {
  BoxSpec turned = table();
  turned.rotate = Vec3(0, 30, 0);
  BoxSpec turning = table();
  turning.motion.keys = {{0.0, Vec3::Zero(), Vec3(0, 30, 0)}, {1.0, Vec3::Zero(), Vec3(0, 30, 0)}};
  const Image still = draw(with_colliders({turned}, 0.5), camera());
  const Image moving = draw(with_colliders({turning}, 0.5), camera());
  EXPECT_LT(pixels_apart(still, moving), 40);
  EXPECT_GT(pixels_apart(still, draw(with_colliders({table()}, 0.5), camera())), 1000);
}

// A deforming mesh is drawn at the snapshot's vertices: grown to 1.2 times
// its size about its centre, it is the still mesh declared that size.
TEST(ColliderLayer, ADeformingMeshIsDrawnAtTheSnapshotsVertices) {
  MeshSpec growing = table_mesh();
  auto mesh = std::make_shared<ObstacleMesh>(*growing.mesh);
  mesh->frame_times = {0.0, 1.0};
  mesh->frames = {mesh->surface.vertices, mesh->surface.vertices};
  for (Vec3& v : mesh->frames[1])
    v = table().center + 1.2 * (v - table().center);
  growing.mesh = mesh;
  MeshSpec grown = table_mesh();
  auto big = std::make_shared<ObstacleMesh>(*grown.mesh);
  big->surface.vertices = mesh->frames[1];
  grown.mesh = big;
  const Image at_end = draw(with_colliders({growing}, 1), camera());
  EXPECT_LT(pixels_apart(at_end, draw(with_colliders({grown}, 0), camera())), 40);
  EXPECT_GT(pixels_apart(at_end, draw(with_colliders({growing}, 0), camera())), 1000);
}

// Frames of a moving collider rewrite its buffers in place, and the still
// copy of the frame (background_cache.h) leaves it out: every frame drawn
// from the copy is the frame drawn from scratch.
TEST(ColliderLayer, MovingCollidersAllocateNothingAndStayOutOfTheStillCopy) {
  BoxSpec moving = table();
  moving.motion.keys = {{0.0, Vec3::Zero(), Vec3::Zero()}, {1.0, Vec3(0.5, 0, 0), Vec3(0, 45, 0)}};
  const FrameSnapshot first = with_colliders({moving, PlaneSpec{}}, 0);
  OsmesaContext context(kW, kH);
  Renderer cached, plain;
  plain.set_background_cache(false);
  const OrbitCamera c = camera();
  long allocations = -1;
  for (const double t : {0.0, 0.3, 0.6, 0.9}) {
    FrameSnapshot s = first;
    s.time = t;
    place_colliders(s.geometry.get(), t, s.colliders);
    cached.draw(s, c, RenderOptions{}, kW, kH);
    const Image a{kW, kH, cached.read_pixels(kW, kH)};
    plain.draw(s, c, RenderOptions{}, kW, kH);
    const Image b{kW, kH, plain.read_pixels(kW, kH)};
    EXPECT_LE(pixels_apart(a, b, 1), 4) << "t = " << t;
    if (allocations < 0) allocations = cached.buffer_allocations();
    EXPECT_EQ(cached.buffer_allocations(), allocations) << "t = " << t;
  }
  EXPECT_GE(cached.background_copies(), 2);
}

}  // namespace
}  // namespace neurocloth
