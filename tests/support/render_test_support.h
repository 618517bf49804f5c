#pragma once
// Shared by the renderer tests: snapshots of the shipped scenes, headless
// frames, and ways to look at the pixels without depending on them exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "core/scene/frame_snapshot.h"
#include "render/orbit_camera.h"
#include "render/osmesa_context.h"
#include "render/render_palette.h"
#include "render/renderer.h"
#include "support/test_support.h"

namespace neurocloth::render_test {

// A shipped scene after `seconds` of simulation, as the renderer sees it.
inline FrameSnapshot scene_snapshot(const std::string& name, double seconds) {
  const Scene scene = test::asset_scene(name);
  Simulation sim = scene.make_simulation();
  sim.advance(seconds);
  EXPECT_EQ(sim.status(), RunStatus::ok) << name;
  FrameSnapshot s;
  s.geometry = make_geometry(scene);
  capture(sim, s);
  return s;
}

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  const std::uint8_t* at(int x, int y) const { return &rgba[4 * (std::size_t(y) * width + x)]; }
};

// One frame through OSMesa, as `neurocloth-cli snapshot` draws it.
inline Image render_headless(const FrameSnapshot& s, const OrbitCamera& camera,
                             const RenderOptions& options, int width, int height) {
  OsmesaContext context(width, height);
  Renderer renderer;
  renderer.draw(s, camera, options, width, height);
  return {width, height, renderer.read_pixels(width, height)};
}

// The cloth's own tones (palette.h): warm, where nothing else in the frame is.
inline bool cloth_coloured(const std::uint8_t* p) {
  return p[0] >= p[2] + 20 && p[0] >= p[1];
}

// Which pixels the cloth's triangles cover when projected with `camera`
// (1 = covered), by rasterising them on the CPU: the truth the frame is held to.
inline std::vector<std::uint8_t> cloth_footprint(const FrameSnapshot& s, const OrbitCamera& c,
                                                 int w, int h) {
  std::vector<std::uint8_t> mask(std::size_t(w) * h, 0);
  std::vector<double> px(s.position.size() / 3), py(px.size());
  for (std::size_t i = 0; i < px.size(); ++i)
    EXPECT_TRUE(c.project(s.node(i), w, h, px[i], py[i]));
  for (const auto& t : s.geometry->triangles) {
    const double x0 = px[t[0]], y0 = py[t[0]], x1 = px[t[1]], y1 = py[t[1]], x2 = px[t[2]],
                 y2 = py[t[2]];
    const double area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0);
    if (area == 0) continue;
    const int xa = std::max(0, int(std::min({x0, x1, x2}))),
              xb = std::min(w - 1, int(std::max({x0, x1, x2})) + 1);
    const int ya = std::max(0, int(std::min({y0, y1, y2}))),
              yb = std::min(h - 1, int(std::max({y0, y1, y2})) + 1);
    for (int y = ya; y <= yb; ++y)
      for (int x = xa; x <= xb; ++x) {
        const double cx = x + 0.5, cy = y + 0.5;
        const double a = ((x1 - cx) * (y2 - cy) - (x2 - cx) * (y1 - cy)) / area;
        const double b = ((x2 - cx) * (y0 - cy) - (x0 - cx) * (y2 - cy)) / area;
        if (a >= 0 && b >= 0 && a + b <= 1) mask[std::size_t(y) * w + x] = 1;
      }
  }
  return mask;
}

// `mask` grown by `r` pixels in every direction (a square neighbourhood).
inline std::vector<std::uint8_t> dilate(const std::vector<std::uint8_t>& mask, int w, int h,
                                        int r) {
  std::vector<std::uint8_t> out(mask.size(), 0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (mask[std::size_t(y) * w + x])
        for (int v = std::max(0, y - r); v <= std::min(h - 1, y + r); ++v)
          for (int u = std::max(0, x - r); u <= std::min(w - 1, x + r); ++u)
            out[std::size_t(v) * w + u] = 1;
  return out;
}

}  // namespace neurocloth::render_test
