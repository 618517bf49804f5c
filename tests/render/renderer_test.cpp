// Headless frames through OSMesa: against committed reference images, and
// against facts that do not depend on exact pixels (where the cloth must
// appear, which side shows, what the strain map and the overlays add).
#include "render/renderer.h"

#include <GL/glew.h>
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "render/cloth_shading.h"
#include "render/gl_program.h"
#include "render/snapshot_framing.h"
#include "support/reference_image.h"
#include "support/scratch_dir.h"

namespace neurocloth {
namespace {

using namespace render_test;
constexpr int kWidth = 480, kHeight = 270;
constexpr double kAspect = double(kWidth) / kHeight;

Image frame(const FrameSnapshot& s, const RenderOptions& o = RenderOptions()) {
  return render_headless(s, framing_camera(s, kAspect), o, kWidth, kHeight);
}

TEST(Renderer, TableDrapeMatchesItsReference) {
  // Draped over the table's edges by 1 s; later frames look the same and cost
  // more simulation, which the sanitizer build feels.
  const FrameSnapshot s = scene_snapshot("table_drape", 1.0);
  expect_matches_reference(frame(s), "table_drape_1s");
}

TEST(Renderer, HangingMatchesItsReference) {
  const FrameSnapshot s = scene_snapshot("hanging", 1.0);
  expect_matches_reference(frame(s), "hanging_1s");
}

TEST(Renderer, HangingWithEveryOverlayMatchesItsReference) {
  const FrameSnapshot s = scene_snapshot("hanging", 1.0);
  RenderOptions o;
  o.strain = o.wireframe = o.springs = o.nodes = true;
  expect_matches_reference(frame(s, o), "hanging_1s_overlays");
}

// The frame's cloth-coloured pixels are where the cloth's triangles project:
// nearly all of the footprint (less a pixel at its edge), nothing well outside.
void expect_cloth_where_it_projects(const FrameSnapshot& s, double inside_share) {
  const OrbitCamera camera = framing_camera(s, kAspect);
  const Image image = render_headless(s, camera, RenderOptions(), kWidth, kHeight);
  const std::vector<std::uint8_t> footprint = cloth_footprint(s, camera, kWidth, kHeight);
  const std::vector<std::uint8_t> near = dilate(footprint, kWidth, kHeight, 2);
  // The footprint's interior: pixels whose whole neighbourhood is footprint.
  std::vector<std::uint8_t> outside(footprint.size());
  for (std::size_t i = 0; i < footprint.size(); ++i)
    outside[i] = !footprint[i];
  const std::vector<std::uint8_t> edge = dilate(outside, kWidth, kHeight, 1);
  std::size_t interior = 0, interior_cloth = 0, far = 0, far_cloth = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t i = std::size_t(y) * kWidth + x;
      const bool cloth = cloth_coloured(image.at(x, y));
      if (footprint[i] && !edge[i]) interior++, interior_cloth += cloth;
      if (!near[i]) far++, far_cloth += cloth;
    }
  ASSERT_GT(interior, std::size_t(kWidth * kHeight / 50))
      << "the cloth should fill some of the frame";
  EXPECT_GT(double(interior_cloth) / interior, inside_share);
  EXPECT_LT(double(far_cloth) / far, 0.001);
}

TEST(Renderer, TheClothAppearsWhereItsTrianglesProject) {
  // Flat above the table (the table is below it, hiding nothing).
  expect_cloth_where_it_projects(scene_snapshot("table_drape", 0), 0.99);
  // Swinging from its pins, folded over itself (which is still cloth).
  expect_cloth_where_it_projects(scene_snapshot("hanging", 1.0), 0.97);
}

bool near_background(const std::uint8_t* p) {
  for (int c = 0; c < 3; ++c)
    if (std::abs(int(p[c]) - int(palette::kBackground[c] * 255 + 0.5f)) > 6) return false;
  return true;
}

// g / r of a lit pixel: about 0.47 for the front tone, 0.81 for the back (palette.h).
double green_over_red(const std::uint8_t* p) {
  return double(p[1]) / std::max(1, int(p[0]));
}

TEST(Renderer, FrontAndBackShowDifferentTones) {
  const FrameSnapshot s = scene_snapshot("hanging", 0);
  ClothShading shading;
  shading.update(s, false);
  const bool front_up = shading.normal[1] > 0;  // the grid's winding decides its front
  OrbitCamera above;
  above.yaw = 0.3, above.pitch = 1.2, above.distance = 2, above.target = Vec3(0.475, 1, 0.475);
  OrbitCamera below = above;
  below.pitch = -1.2;
  const double ratio_above =
      green_over_red(render_headless(s, above, {}, kWidth, kHeight).at(kWidth / 2, kHeight / 2));
  const double ratio_below =
      green_over_red(render_headless(s, below, {}, kWidth, kHeight).at(kWidth / 2, kHeight / 2));
  const double front = front_up ? ratio_above : ratio_below;
  const double back = front_up ? ratio_below : ratio_above;
  EXPECT_LT(front, 0.6);
  EXPECT_GT(back, 0.7);
}

TEST(Renderer, TheStrainMapIsRedWhereTheClothIsStretched) {
  // At 0.5 s the cloth swings through the vertical below its pins, pulling hardest on them.
  const FrameSnapshot s = scene_snapshot("hanging", 0.5);
  RenderOptions o;
  o.strain = true;
  // Face on, from the side the cloth swung away from.
  OrbitCamera camera;
  camera.yaw = 0, camera.pitch = 0.1;
  const Bounds b = snapshot_bounds(s);
  camera.frame(b.lo, b.hi, kAspect);
  const Image image = render_headless(s, camera, o, kWidth, kHeight);
  ClothShading shading;
  shading.update(s, true);
  // Sample the frame where each node projects; a node may be hidden behind a
  // fold, so the test asks for most of them, not all.
  int stretched = 0, stretched_red = 0, relaxed = 0, relaxed_red = 0;
  for (std::size_t i = 0; i < shading.strain.size(); ++i) {
    double px, py;
    ASSERT_TRUE(camera.project(s.node(i), kWidth, kHeight, px, py));
    ASSERT_TRUE(px >= 0 && px < kWidth && py >= 0 && py < kHeight);
    const std::uint8_t* p = image.at(int(px), int(py));
    if (near_background(p)) continue;  // a node on the outline, its pixel just outside
    // Lit, the map's colour at 0.8 has red about 90 levels above blue; at 0.2, below it.
    const bool red = p[0] > p[2] + 40;
    if (shading.strain[i] > 0.8f * o.strain_max) stretched++, stretched_red += red;
    if (shading.strain[i] < 0.2f * o.strain_max) relaxed++, relaxed_red += red;
  }
  ASSERT_GE(stretched, 2) << "hanging.json's pins should stretch the cloth near them";
  ASSERT_GE(relaxed, 100);
  EXPECT_GE(double(stretched_red) / stretched, 0.6);
  EXPECT_LE(double(relaxed_red) / relaxed, 0.1);
  // The pins (nodes 0 and 19) carry the weight: red around them in the frame.
  for (const int pin : {0, 19}) {
    double px, py;
    ASSERT_TRUE(camera.project(s.node(pin), kWidth, kHeight, px, py));
    int reddest = -255;
    for (int y = std::max(0, int(py) - 4); y <= std::min(kHeight - 1, int(py) + 4); ++y)
      for (int x = std::max(0, int(px) - 4); x <= std::min(kWidth - 1, int(px) + 4); ++x)
        reddest = std::max(reddest, int(image.at(x, y)[0]) - int(image.at(x, y)[2]));
    EXPECT_GT(reddest, 80) << "pin " << pin;
  }
}

TEST(Renderer, AClothAtRestIsBlueOnTheStrainMapWithALegendBesideIt) {
  const FrameSnapshot s = scene_snapshot("table_drape", 0);
  RenderOptions o;
  o.strain = true;
  const Image image = frame(s, o);
  int blue = 0, red = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth * 3 / 4; ++x) {  // the legend is at the right edge
      const std::uint8_t* p = image.at(x, y);
      blue += p[2] > p[0] + 60;
      red += p[0] > p[2] + 60;
    }
  EXPECT_GT(blue, kWidth * kHeight / 50);
  EXPECT_EQ(red, 0);
  // The legend's bar: red at its top, blue at its bottom, a few pixels in from the right.
  const int x = kWidth - int(24.0 * kHeight / 720) - 4;
  const int top = kHeight - int(264.0 * kHeight / 720) + 3,
            bottom = kHeight - int(24.0 * kHeight / 720) - 3;
  EXPECT_GT(image.at(x, top)[0], image.at(x, top)[2] + 80);
  EXPECT_GT(image.at(x, bottom)[2], image.at(x, bottom)[0] + 80);
}

// How many pixels of a and b differ at all.
int changed_pixels(const Image& a, const Image& b) {
  int n = 0;
  for (std::size_t i = 0; i < a.rgba.size(); i += 4)
    n += a.rgba[i] != b.rgba[i] || a.rgba[i + 1] != b.rgba[i + 1] || a.rgba[i + 2] != b.rgba[i + 2];
  return n;
}

TEST(Renderer, EachOptionChangesTheFrame) {
  const FrameSnapshot s = scene_snapshot("table_drape", 0);
  const Image plain = frame(s);
  EXPECT_EQ(changed_pixels(plain, frame(s)), 0) << "the same frame twice must be identical";
  for (bool RenderOptions::*flag : {&RenderOptions::wireframe, &RenderOptions::springs,
                                    &RenderOptions::nodes, &RenderOptions::strain}) {
    RenderOptions o;
    o.*flag = true;
    EXPECT_GT(changed_pixels(plain, frame(s, o)), kWidth * kHeight / 100);
  }
  for (bool RenderOptions::*flag : {&RenderOptions::grid, &RenderOptions::colliders}) {
    RenderOptions o;
    o.*flag = false;
    EXPECT_GT(changed_pixels(plain, frame(s, o)), kWidth * kHeight / 100);
  }
  // Without colliders or grid, what is not cloth is background.
  RenderOptions bare;
  bare.grid = bare.colliders = false;
  const Image only_cloth = frame(s, bare);
  int other = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::uint8_t* p = only_cloth.at(x, y);
      const int bg[3] = {int(palette::kBackground[0] * 255 + 0.5f),
                         int(palette::kBackground[1] * 255 + 0.5f),
                         int(palette::kBackground[2] * 255 + 0.5f)};
      const bool background =
          std::abs(p[0] - bg[0]) <= 1 && std::abs(p[1] - bg[1]) <= 1 && std::abs(p[2] - bg[2]) <= 1;
      other += !background && !cloth_coloured(p);
    }
  EXPECT_LT(other, kWidth * kHeight / 200);  // a few blended edge pixels
}

TEST(Renderer, AppliedForcesAreDrawnAsLinesOverEverything) {
  FrameSnapshot s = scene_snapshot("hanging", 0);
  const OrbitCamera camera = framing_camera(s, kAspect);
  // A pull from one corner (node 399) towards a point under the opposite one:
  // seen from above, the cloth is in front of most of the line.
  const Vec3 anchor = s.node(0) + Vec3(0, -0.04, 0);
  s.forces.push_back({399, Vec3(0, -1, 0), anchor});
  const Image image = render_headless(s, camera, RenderOptions(), kWidth, kHeight);
  double ax, ay, bx, by;
  ASSERT_TRUE(camera.project(s.node(399), kWidth, kHeight, ax, ay));
  ASSERT_TRUE(camera.project(anchor, kWidth, kHeight, bx, by));
  int on_line = 0, samples = 0;
  for (double t = 0.1; t <= 0.9; t += 0.05, ++samples) {
    const int x = int(ax + t * (bx - ax)), y = int(ay + t * (by - ay));
    ASSERT_TRUE(x >= 1 && x < kWidth - 1 && y >= 1 && y < kHeight - 1);
    bool hit = false;
    for (int v = y - 1; v <= y + 1; ++v)
      for (int u = x - 1; u <= x + 1; ++u) {
        const std::uint8_t* p = image.at(u, v);
        hit |= p[0] > p[1] + 80 && p[2] > p[1] + 60;  // the force's magenta
      }
    on_line += hit;
  }
  EXPECT_GE(on_line, samples - 1);
  RenderOptions no_forces;
  no_forces.forces = false;
  const Image hidden = render_headless(s, camera, no_forces, kWidth, kHeight);
  s.forces.clear();
  EXPECT_EQ(changed_pixels(hidden, render_headless(s, camera, {}, kWidth, kHeight)), 0);
}

TEST(Renderer, BuffersAreReusedForFramesOfTheSameSize) {
  const Scene scene = test::asset_scene("table_drape");
  Simulation sim = scene.make_simulation();
  FrameSnapshot s;
  s.geometry = make_geometry(scene);
  capture(sim, s);
  OsmesaContext context(kWidth, kHeight);
  Renderer renderer;
  RenderOptions all;
  all.strain = all.wireframe = all.springs = all.nodes = true;
  s.forces.push_back({0, Vec3(0, 1, 0), Vec3(0, 2, 0)});
  const OrbitCamera camera = framing_camera(s, kAspect);
  renderer.draw(s, camera, all, kWidth, kHeight);
  const long after_first = renderer.buffer_allocations();
  EXPECT_GT(after_first, 0);
  for (int frame = 0; frame < 5; ++frame) {
    sim.advance(0.02);
    capture(sim, s);
    renderer.draw(s, camera, frame % 2 ? all : RenderOptions(), kWidth, kHeight);
  }
  EXPECT_EQ(renderer.buffer_allocations(), after_first);
}

TEST(Renderer, ASnapshotThatDisagreesWithItsGeometryIsRefused) {
  FrameSnapshot s = scene_snapshot("hanging", 0);
  s.position.resize(s.position.size() - 3);
  OsmesaContext context(64, 64);
  Renderer renderer;
  EXPECT_THROW(renderer.draw(s, OrbitCamera(), {}, 64, 64), std::invalid_argument);
  auto broken = std::make_shared<SceneGeometry>(*s.geometry);
  broken->triangles.push_back({0, 1, 400});
  s.geometry = broken;
  s.position.resize(3 * 400);
  EXPECT_THROW(renderer.draw(s, OrbitCamera(), {}, 64, 64), std::invalid_argument);
  // The same refused scene again (a window redraws its last snapshot): refused
  // again, not drawn with the index it refused.
  RenderOptions all;
  all.strain = all.wireframe = all.springs = all.nodes = true;
  EXPECT_THROW(renderer.draw(s, OrbitCamera(), all, 64, 64), std::invalid_argument);
}

TEST(Renderer, AMissingShaderIsNamed) {
  OsmesaContext context(16, 16);
  try {
    Renderer renderer("/nonexistent/shaders");
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/shaders/"), std::string::npos) << e.what();
  }
}

// A shader the driver refuses: the message names the file and carries the
// driver's own log (read for the shader when it does not compile, for the
// program when it does not link).
TEST(Renderer, ABrokenShaderIsNamedWithTheDriversMessage) {
  OsmesaContext context(16, 16);
  const std::filesystem::path dir = test::scratch_dir();
  const auto write = [&](const char* name, const char* text) {
    std::ofstream(dir / name, std::ios::binary | std::ios::trunc) << text;
  };
  write("ok.vert", "#version 330 core\nvoid main() { gl_Position = vec4(0.0); }\n");
  write("bad.vert", "#version 330 core\nvoid main() { gl_Position = vec4(undeclared_thing); }\n");
  write("ok.frag", "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(1.0); }\n");
  // Each stage compiles alone; the program has no entry point for its fragments.
  write("nomain.frag", "#version 330 core\nout vec4 c;\nvoid helper() { c = vec4(1.0); }\n");
  const auto message = [&](const char* vertex, const char* fragment) -> std::string {
    try {
      GlProgram program(dir.string(), vertex, fragment);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(message("ok.vert", "ok.frag"), "");  // the oracle: a sound pair builds
  const std::string compile = message("bad.vert", "ok.frag");
  EXPECT_NE(compile.find("bad.vert: does not compile: "), std::string::npos) << compile;
  EXPECT_NE(compile.find("undeclared_thing"), std::string::npos) << compile;
  const std::string link = message("ok.vert", "nomain.frag");
  EXPECT_NE(link.find("does not link: "), std::string::npos) << link;
  const std::size_t log = link.find("does not link: ");
  EXPECT_NE(link.find("main", log), std::string::npos) << link;  // in the driver's log
}

// Linking libGL into a headless program binds the GL 1.x calls to glvnd's
// stubs, which draw nothing (docs/rendering.md): they must come from OSMesa.
TEST(Renderer, HeadlessProgramsTakeTheirGlCallsFromOsmesa) {
  for (void* f : {reinterpret_cast<void*>(&glClear), reinterpret_cast<void*>(&glReadPixels),
                  reinterpret_cast<void*>(&glDrawElements)}) {
    Dl_info info{};
    ASSERT_NE(dladdr(f, &info), 0);
    ASSERT_NE(info.dli_fname, nullptr);
    EXPECT_NE(std::string(info.dli_fname).find("libOSMesa"), std::string::npos) << info.dli_fname;
  }
}

TEST(Renderer, ReportsTheHeadlessRenderer) {
  OsmesaContext context(16, 16);
  EXPECT_NE(context.renderer_string().find("Mesa"), std::string::npos) << context.renderer_string();
  EXPECT_THROW(OsmesaContext(0, 10), std::runtime_error);
}

}  // namespace
}  // namespace neurocloth

namespace neurocloth {
namespace {

using namespace render_test;

// A grid cloth above kCoarseGridFrom rows is also triangulated on every other
// row and column, the last kept, wound as the full one; smaller ones are not.
TEST(CoarseTriangles, KeepEveryOtherRowAndColumnAndTheLast) {
  const Scene drape = test::asset_scene("table_drape");
  EXPECT_TRUE(make_geometry(resized_grid(drape, kCoarseGridFrom))->coarse_triangles.empty());
  for (const int n : {kCoarseGridFrom + 1, kCoarseGridFrom + 2}) {
    const Scene big = resized_grid(drape, n);
    const auto g = make_geometry(big);
    const int kept = (n + 1) / 2 + (n % 2 == 0);  // 0, 2, ..., and n - 1 when n is even
    ASSERT_EQ(g->coarse_triangles.size(), std::size_t(2 * (kept - 1) * (kept - 1))) << n;
    // Same winding: each coarse triangle faces the way the full cloth's first one does.
    const auto& p = big.topology.rest_positions;
    auto normal = [&](const std::array<std::int32_t, 3>& t) {
      return (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).normalized();
    };
    const Vec3 up = normal(g->triangles.front());
    double area = 0;
    for (const auto& t : g->coarse_triangles) {
      for (const std::int32_t i : t)
        ASSERT_TRUE(i >= 0 && std::size_t(i) < p.size());
      EXPECT_GT(normal(t).dot(up), 0.999);
      area += 0.5 * (p[t[1]] - p[t[0]]).cross(p[t[2]] - p[t[0]]).norm();
    }
    // They cover the whole cloth, no more.
    const double side = big.grid->spacing * (n - 1);
    EXPECT_NEAR(area, side * side, 1e-9 * side * side) << n;
  }
}

// The window draws a large grid from them: on the flat cloth the frame is the
// full one's; snapshots (no limit) draw every triangle.
TEST(CoarseTriangles, DrawTheSameFlatClothAsTheFullMesh) {
  const Scene big = resized_grid(test::asset_scene("table_drape"), kCoarseGridFrom + 1);
  Simulation sim = big.make_simulation();
  FrameSnapshot s;
  s.geometry = make_geometry(big);
  capture(sim, s);
  const Image full = frame(s);
  RenderOptions limited;
  limited.max_cloth_triangles = s.geometry->triangles.size() - 1;
  const Image coarse = frame(s, limited);
  // Measured: not a pixel apart (flat, every vertex the same normal and tone).
  EXPECT_EQ(changed_pixels(full, coarse), 0);
  RenderOptions roomy;
  roomy.max_cloth_triangles = s.geometry->triangles.size();  // not above it: every triangle
  EXPECT_EQ(changed_pixels(full, frame(s, roomy)), 0);
  // And the limited frame is drawn from the coarse triangles: half of them gone
  // leaves a hole.
  auto holed = std::make_shared<SceneGeometry>(*s.geometry);
  holed->coarse_triangles.resize(holed->coarse_triangles.size() / 2);
  FrameSnapshot h = s;
  h.geometry = holed;
  EXPECT_GT(changed_pixels(full, frame(h, limited)), kWidth * kHeight / 50);
  EXPECT_EQ(changed_pixels(full, frame(h)), 0);
}

}  // namespace
}  // namespace neurocloth
