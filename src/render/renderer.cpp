#include "render/renderer.h"

#include <GL/glew.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "render/background_cache.h"
#include "render/cloth_layer.h"
#include "render/collider_layer.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/grid_layer.h"
#include "render/legend_text.h"
#include "render/line_layer.h"
#include "render/render_palette.h"
#include "render/surface_program.h"

namespace neurocloth {
namespace {

// Plane colliders reach this many grid sizes: to the horizon of any framed view.
constexpr double kPlaneReach = 25;

void check_gl(const char* where) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "0x%04x", unsigned(e));
    throw std::runtime_error(std::string("OpenGL error ") + code + " in " + where);
  }
}

std::string percent_label(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100 * fraction);
  return text;
}

}  // namespace

// GL objects live as long as the renderer. Buffers that change every frame
// (positions, normals, strain, overlays, moving colliders) keep their storage
// between frames; the scene's fixed parts (triangles, springs, still
// colliders, grid) are uploaded again only when a snapshot arrives with a
// different SceneGeometry.
struct Renderer::Impl {
  SurfaceProgram surface;  // the cloth's and the colliders'
  ClothLayer cloth;
  LineLayer lines;
  GlProgram legend;
  GLint legend_viewport;

  ColliderLayer colliders;
  enum Vao { legend_vao, kVaoCount };
  GLuint vao[kVaoCount] = {};
  GlBuffer legend_quad;

  std::shared_ptr<const SceneGeometry> geometry;  // what the fixed buffers hold
  bool geometry_uploaded = false;
  GridLayer grid;
  BackgroundCache background;

  explicit Impl(const std::string& dir)
      : surface(dir),
        lines(dir, cloth),
        legend(dir, "legend.vert", "legend.frag", {"strain_colour.glsl"}),
        grid(dir) {
    legend_viewport = legend.uniform("u_viewport");
    glGenVertexArrays(kVaoCount, vao);
    glBindVertexArray(vao[legend_vao]);
    vertex_attribute(vertex_slot::position, legend_quad, 2, 3, 0);
    vertex_attribute(vertex_slot::scalar, legend_quad, 1, 3, 2);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    check_gl("Renderer()");
  }

  ~Impl() { glDeleteVertexArrays(kVaoCount, vao); }

  long allocations() const {
    return cloth.allocations() + lines.allocations() + colliders.allocations() +
           legend_quad.allocations() + grid.allocations();
  }

  void upload_geometry(const FrameSnapshot& s);
  void upload_frame(const FrameSnapshot& s, const RenderOptions& o);
  // The still part of a frame: the clear, the still colliders, the ground grid.
  void draw_background(const OrbitCamera& camera, const Eigen::Matrix4f& vp,
                       const RenderOptions& o);
  void draw_legend(const RenderOptions& o, int width, int height);
};

void Renderer::Impl::upload_geometry(const FrameSnapshot& s) {
  // Not uploaded until every check below has passed: a refused scene drawn
  // again is checked again, never drawn from what its refusal left.
  geometry_uploaded = false;
  geometry = s.geometry;
  // Both layers let go of the scene before either checks the new one, so that
  // a scene refused halfway leaves nothing of the one before to draw.
  cloth.forget_geometry();
  lines.forget_geometry();
  if (geometry) {
    cloth.upload_geometry(*geometry);
    lines.upload_geometry(*geometry);
  }
  grid.place(s);
  const GroundGrid& ground = grid.ground();
  colliders.upload_geometry(geometry.get(), ground.centre, kPlaneReach * ground.half_size(),
                            s.time);
  geometry_uploaded = true;
}

void Renderer::Impl::upload_frame(const FrameSnapshot& s, const RenderOptions& o) {
  if (geometry && (s.position.size() != 3 * geometry->node_count))
    throw std::invalid_argument("Renderer: the snapshot has " + std::to_string(s.position.size()) +
                                " coordinates for " + std::to_string(geometry->node_count) +
                                " nodes");
  cloth.upload_frame(s, o.strain);
  lines.upload_frame(s, o.nodes);
  if (o.colliders) colliders.upload_frame(s);
}

void Renderer::Impl::draw_background(const OrbitCamera& camera, const Eigen::Matrix4f& vp,
                                     const RenderOptions& o) {
  const palette::Colour& bg = palette::kBackground;
  glClearColor(bg[0], bg[1], bg[2], 1);
  glClearDepth(1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (o.colliders) colliders.draw_still(surface, camera, vp, o.strain_max);
  // Blended over the colliders and the clear without writing depth, so it hides
  // nothing drawn later; the cloth, opaque, covers it where it is in front.
  if (o.grid) grid.draw(camera, vp);
}

void Renderer::Impl::draw_legend(const RenderOptions& o, int width, int height) {
  // A vertical bar at the right edge, 0 at the bottom and strain_max at the top,
  // labelled with both ends in percent.
  const float unit = float(height) / 720.0f;
  const float bar_w = 18 * unit, bar_h = 240 * unit, margin = 24 * unit;
  const float x1 = float(width) - margin, x0 = x1 - bar_w;
  const float y1 = float(height) - margin, y0 = y1 - bar_h;
  const float quad[] = {x0, y1, 0, x1, y1, 0, x0, y0, 1, x1, y0, 1};
  legend_quad.upload(quad, sizeof quad);
  glDisable(GL_DEPTH_TEST);
  legend.use();
  glUniform2f(legend_viewport, float(width), float(height));
  glBindVertexArray(vao[legend_vao]);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);

  // The frame and the labels, as lines in pixels.
  std::vector<float> segments = {x0, y0, x1, y0, x1, y0, x1, y1, x1, y1, x0, y1, x0, y1, x0, y0};
  const float text_h = std::max(9.0f, 14 * unit), gap = 8 * unit;
  const std::string top = percent_label(o.strain_max), bottom = percent_label(0);
  append_label(top, x0 - gap - label_width(top, text_h), y0 + text_h, text_h, segments);
  append_label(bottom, x0 - gap - label_width(bottom, text_h), y1, text_h, segments);
  lines.draw_in_pixels(segments, palette::kLegendText, width, height);
  glEnable(GL_DEPTH_TEST);
}

Renderer::Renderer(const std::string& shader_dir) : impl_(std::make_unique<Impl>(shader_dir)) {}

Renderer::~Renderer() = default;

void Renderer::draw(const FrameSnapshot& snapshot, const OrbitCamera& camera,
                    const RenderOptions& options, int width, int height,
                    const std::vector<float>* ghost_points) {
  if (width < 1 || height < 1) return;  // a minimised window
  Impl& m = *impl_;
  if (snapshot.geometry != m.geometry || !m.geometry_uploaded) m.upload_geometry(snapshot);
  m.upload_frame(snapshot, options);

  glViewport(0, 0, width, height);
  // Everything the renderer relies on is set here: the window's UI may have
  // changed any of it since the last frame.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LEQUAL);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);  // two-sided cloth
  glDisable(GL_SCISSOR_TEST);
  glDisable(GL_BLEND);
  glEnable(GL_PROGRAM_POINT_SIZE);
  glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);

  const Eigen::Matrix4f vp = camera.projection(double(width) / height) * camera.view();
  const BackgroundKey key{vp,           camera.target.cast<float>(), width,           height,
                          options.grid, options.colliders,           m.geometry.get()};
  bool copied = false;
  if (m.background.worth_using(key)) {
    check_gl("Renderer::draw, before the background's copy");
    if (!m.background.holds(key) && m.background.begin_capture(key)) {
      m.draw_background(camera, vp, options);
      m.background.end_capture();
    }
    copied = m.background.holds(key) && m.background.copy_to_window();
  }
  if (!copied) m.draw_background(camera, vp, options);
  // Moving colliders are not part of the still copy: drawn every frame, after
  // the grid (which they cover where they dip below it, as the cloth does).
  if (options.colliders) m.colliders.draw_moving(m.surface, camera, vp, options.strain_max);
  m.cloth.draw(m.surface, camera, vp, options);
  m.lines.draw(vp, snapshot, options, height);
  if (ghost_points) m.lines.draw_ghosts(vp, *ghost_points, height);
  if (options.strain) m.draw_legend(options, width, height);
  glBindVertexArray(0);
  glUseProgram(0);
  check_gl("Renderer::draw");
}

std::vector<std::uint8_t> Renderer::read_pixels(int width, int height) const {
  std::vector<std::uint8_t> rgba(std::size_t(width) * std::size_t(height) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  check_gl("Renderer::read_pixels");
  // OpenGL's rows start at the bottom; images start at the top.
  const std::size_t row = std::size_t(width) * 4;
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(rgba.begin() + std::ptrdiff_t(y * row),
                     rgba.begin() + std::ptrdiff_t((y + 1) * row),
                     rgba.begin() + std::ptrdiff_t((height - 1 - y) * row));
  return rgba;
}

void Renderer::set_background_cache(bool on) {
  impl_->background.set_enabled(on);
}

long Renderer::background_copies() const {
  return impl_->background.copies();
}

long Renderer::background_captures() const {
  return impl_->background.captures();
}

long Renderer::buffer_allocations() const {
  return impl_->allocations();
}

std::string Renderer::default_shader_dir() {
  const char* env = std::getenv("NEUROCLOTH_SHADERS");
  return env && *env ? env : NEUROCLOTH_SHADERS_DIR;
}

}  // namespace neurocloth
