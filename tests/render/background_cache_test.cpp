// While the camera is still, a frame starts from an offscreen copy of the
// clear, the colliders and the grid (background_cache.h). Every such frame
// must be the frame drawn from scratch: with the cloth moved on, after the
// camera moved, with the grid or the colliders switched.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>

#include "render/snapshot_framing.h"
#include "support/render_test_support.h"

namespace neurocloth {
namespace {

using namespace render_test;

constexpr int kCacheWidth = 480, kCacheHeight = 270;

// Pixels with a channel more than one level apart.
int pixels_apart(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b) {
  EXPECT_EQ(a.size(), b.size());
  int n = 0;
  for (std::size_t i = 0; i + 3 < std::min(a.size(), b.size()); i += 4) {
    int worst = 0;
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, std::abs(int(a[i + c]) - int(b[i + c])));
    n += worst > 1;
  }
  return n;
}

TEST(BackgroundCache, EveryFrameFromTheCopyIsTheFrameDrawnFromScratch) {
  const FrameSnapshot early = scene_snapshot("table_drape", 0.3);
  FrameSnapshot late = scene_snapshot("table_drape", 0.6);
  late.geometry = early.geometry;  // one scene: the copy's colliders and grid stay valid
  const OrbitCamera framed = framing_camera(early, double(kCacheWidth) / kCacheHeight);
  OrbitCamera turned = framed;
  turned.yaw += 0.4;

  OsmesaContext context(kCacheWidth, kCacheHeight);
  Renderer cached, plain;
  plain.set_background_cache(false);
  auto expect_same = [&](const FrameSnapshot& s, const OrbitCamera& c, const RenderOptions& o,
                         const char* what) {
    cached.draw(s, c, o, kCacheWidth, kCacheHeight);
    const std::vector<std::uint8_t> a = cached.read_pixels(kCacheWidth, kCacheHeight);
    plain.draw(s, c, o, kCacheWidth, kCacheHeight);
    const std::vector<std::uint8_t> b = plain.read_pixels(kCacheWidth, kCacheHeight);
    // The copied depth may settle a pixel or two where the cloth lies on the
    // table the other way (measured: one pixel of 129,600); a stale or wrong
    // copy differs by thousands.
    EXPECT_LE(pixels_apart(a, b), 4) << what;
  };
  RenderOptions o;
  expect_same(early, framed, o, "first frame (drawn, nothing to copy yet)");
  expect_same(early, framed, o, "second frame (the copy made)");
  expect_same(late, framed, o, "the cloth moved on, over the copy");
  EXPECT_EQ(cached.background_captures(), 1);
  EXPECT_EQ(cached.background_copies(), 2);
  expect_same(late, turned, o, "the camera turned");
  expect_same(late, turned, o, "still again: a new copy");
  EXPECT_EQ(cached.background_captures(), 2);
  RenderOptions no_grid = o;
  no_grid.grid = false;
  expect_same(late, turned, no_grid, "grid off");
  expect_same(late, turned, no_grid, "grid off, copied");
  RenderOptions no_colliders = o;
  no_colliders.colliders = false;
  expect_same(late, turned, no_colliders, "colliders off");
  expect_same(late, turned, no_colliders, "colliders off, copied");
  RenderOptions overlays = o;
  overlays.strain = overlays.wireframe = overlays.nodes = true;
  expect_same(late, turned, overlays, "overlays on (after colliders off: drawn)");
  EXPECT_EQ(cached.background_captures(), 4);
  EXPECT_EQ(cached.background_copies(), 5);  // not the overlays' frame: the camera had not stayed
  EXPECT_EQ(plain.background_copies(), 0);
}

}  // namespace
}  // namespace neurocloth
