#pragma once
// Draws a FrameSnapshot with OpenGL 3.3 core (through GLEW): the cloth smooth
// shaded and lit on both sides (front and back in different tones, normals
// recomputed every frame), the colliders, a ground grid; optionally wireframe,
// springs coloured by family, nodes, and a strain colour map (blue -> red by
// stretch) with its legend. It only ever reads the snapshot it is given.
// The same code draws into a GLFW window and into an OSMesa buffer.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "core/scene/frame_snapshot.h"
#include "render/orbit_camera.h"

namespace neurocloth {

struct RenderOptions {
  bool wireframe = false;
  bool springs = false;  // coloured by family
  bool nodes = false;
  bool strain = false;  // colour map by stretch, with a legend
  bool grid = true;
  bool colliders = true;
  bool forces = true;       // applied forces as lines
  float strain_max = 0.1f;  // stretch at the red end of the map (0.1 = 10%)
  // 0: every triangle of the cloth. Above this many, a grid cloth's surface is
  // drawn from SceneGeometry::coarse_triangles (every other row and column;
  // its shading still from every triangle): what the window sets, since on a
  // software rasteriser the triangles are the frame's cost (docs/rendering.md,
  // "Large cloths"). Snapshots draw every triangle.
  std::size_t max_cloth_triangles = 0;
};

// The window's RenderOptions::max_cloth_triangles: llvmpipe on two cores draws
// the 128 x 128 cloth (32,258 triangles) at 60 frames/s and 256 x 256 (130,050)
// at 34 with nothing else running (docs/rendering.md, "Large cloths").
inline constexpr std::size_t kWindowClothTriangles = 40000;

class Renderer {
 public:
  // Needs a current OpenGL 3.3 core context with GLEW initialised. Reads the
  // shaders from `shader_dir` (default: the installed shaders/ folder); throws
  // std::runtime_error naming the file and the compiler's message on failure.
  explicit Renderer(const std::string& shader_dir = default_shader_dir());
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // `ghost_points` (x, y, z per point, m; may be null): a reference motion's
  // nodes, drawn as small discs in their own colour over everything.
  void draw(const FrameSnapshot& snapshot, const OrbitCamera& camera, const RenderOptions& options,
            int width, int height, const std::vector<float>* ghost_points = nullptr);
  // While the camera stays still, the clear, the colliders and the grid are
  // drawn once into an offscreen copy and each frame starts from it
  // (background_cache.h). On by default; off, every frame draws everything.
  void set_background_cache(bool on);
  // Frames drawn from that copy, and times the copy was (re)drawn, so far.
  long background_copies() const;
  long background_captures() const;
  // The current framebuffer as RGBA, 8 bits per channel, top row first.
  std::vector<std::uint8_t> read_pixels(int width, int height) const;
  // How often a GL buffer was (re)allocated so far: frames of a size already
  // drawn allocate nothing, which the tests check with this count.
  long buffer_allocations() const;

  static std::string default_shader_dir();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Writes RGBA pixels (top row first) as a PNG, atomically (a temporary file
// beside it, renamed into place); throws std::runtime_error naming the path and
// leaves no file behind.
void write_png(const std::string& path, const std::vector<std::uint8_t>& rgba, int width,
               int height);
// Reads a PNG as RGBA (for tests comparing against reference images).
std::vector<std::uint8_t> read_png(const std::string& path, int& width, int& height);

}  // namespace neurocloth
