// The ground grid is drawn on strips a few pixels wide around its lines
// (shaders/grid.vert). Widened to half a cell, the strips tile the grid's whole
// square, which is how the grid was drawn before: every pixel the square gives
// a line must be inside a strip, so the two frames must match.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "render_test_support.h"

namespace neurocloth {
namespace {

using namespace render_test;

constexpr int kWidth = 480, kHeight = 270;

// The shaders with grid.vert's strips widened to half a cell everywhere.
std::string whole_square_shaders() {
  const std::filesystem::path dir =
      std::filesystem::path(NEUROCLOTH_TEST_TMP) / "render" / "whole_square_shaders";
  std::filesystem::create_directories(dir);
  for (const auto& f : std::filesystem::directory_iterator(Renderer::default_shader_dir()))
    std::filesystem::copy_file(f.path(), dir / f.path().filename(),
                               std::filesystem::copy_options::overwrite_existing);
  std::ifstream in(dir / "grid.vert");
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  const std::string line = "  v_world = a_centre + half_width * across;";
  const std::size_t at = s.find(line);
  EXPECT_NE(at, std::string::npos) << "grid.vert no longer places its strips as this test expects";
  if (at != std::string::npos) s.insert(at, "  half_width = max(half_width, u_max_half_width);\n");
  std::ofstream(dir / "grid.vert") << s;
  return dir.string();
}

Image draw(const FrameSnapshot& s, const OrbitCamera& camera, const std::string& shader_dir,
           bool grid = true) {
  OsmesaContext context(kWidth, kHeight);
  Renderer renderer(shader_dir);
  RenderOptions o;
  o.colliders = false;  // more grid in view
  o.grid = grid;
  renderer.draw(s, camera, o, kWidth, kHeight);
  return {kWidth, kHeight, renderer.read_pixels(kWidth, kHeight)};
}

TEST(GridStrips, DrawWhatTheWholeSquareDraws) {
  const FrameSnapshot s = scene_snapshot("table_drape", 0);
  const std::string wide = whole_square_shaders();
  // Framed, from high above, grazing the ground, from below it, and close to it.
  const char* cameras[] = {"0.6,0.45,2.3", "0,1.5,6", "0.3,0.05,4", "1.2,-0.3,2",
                           "2.5,0.02,1.5,0,0.05,0"};
  for (const char* text : cameras) {
    const OrbitCamera camera = parse_camera(text, Vec3(0, 0.4, 0));
    const Image strips = draw(s, camera, Renderer::default_shader_dir());
    const Image square = draw(s, camera, wide);
    const Image bare = draw(s, camera, Renderer::default_shader_dir(), false);
    std::size_t off = 0, grid = 0;
    for (std::size_t i = 0; i < strips.rgba.size(); i += 4) {
      int worst = 0;
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, std::abs(int(strips.rgba[i + c]) - int(square.rgba[i + c])));
      off += worst > 2;
      grid += square.rgba[i] != bare.rgba[i];
    }
    EXPECT_EQ(off, 0u) << "camera " << text << ": pixels the strips miss";
    EXPECT_GT(grid, 1000u) << "camera " << text << ": hardly any grid in view";
  }
}

}  // namespace
}  // namespace neurocloth
