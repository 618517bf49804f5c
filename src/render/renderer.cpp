#include "render/renderer.h"

#include <GL/glew.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

#include "render/background_cache.h"
#include "render/cloth_shading.h"
#include "render/collider_meshes.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/grid_layer.h"
#include "render/legend_text.h"
#include "render/render_palette.h"

namespace neurocloth {
namespace {

constexpr int kOverlayFloats = 7;  // x, y, z, r, g, b, a
// Plane colliders reach this many grid sizes: to the horizon of any framed view.
constexpr double kPlaneReach = 25;

// Maps pixels (origin top left, y down) to clip space, for the 2D legend.
Eigen::Matrix4f pixel_projection(int width, int height) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(0, 0) = 2.0f / float(width);
  m(0, 3) = -1;
  m(1, 1) = -2.0f / float(height);
  m(1, 3) = 1;
  return m;
}

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
// (positions, normals, strain, overlays) keep their storage between frames;
// the scene's fixed parts (triangles, springs, colliders, grid) are uploaded
// again only when a snapshot arrives with a different SceneGeometry.
struct Renderer::Impl {
  GlProgram surface, lines, legend;
  struct {
    GLint view_projection, front, back, use_strain, strain_max, eye, key;
  } su;
  struct {
    GLint view_projection, point_size, round_points;
  } lu;
  GLint legend_viewport;

  enum Vao {
    cloth_vao,
    coarse_vao,
    wire_vao,
    springs_vao,
    nodes_vao,
    collider_vao,
    overlay_vao,
    ghost_vao,
    legend_vao,
    kVaoCount
  };
  GLuint vao[kVaoCount] = {};
  GlBuffer position, normal, strain, triangles, coarse_triangles, spring_pairs, node_colour;
  GlBuffer collider_position, collider_normal, collider_index, overlay, legend_quad, ghost;

  std::shared_ptr<const SceneGeometry> geometry;  // what the fixed buffers hold
  std::size_t triangle_indices = 0, coarse_indices = 0;
  std::size_t spring_begin[kSpringFamilyCount + 1] = {};  // index ranges by family
  std::size_t collider_indices = 0;
  bool geometry_uploaded = false;
  GridLayer grid;
  BackgroundCache background;

  // Per-frame scratch, kept for its storage.
  ClothShading shading;
  std::vector<float> colours, overlay_data;

  explicit Impl(const std::string& dir)
      : surface(dir, "surface.vert", "surface.frag", {"strain_colour.glsl"}),
        lines(dir, "lines.vert", "lines.frag"),
        legend(dir, "legend.vert", "legend.frag", {"strain_colour.glsl"}),
        grid(dir) {
    su = {surface.uniform("u_view_projection"), surface.uniform("u_front_colour"),
          surface.uniform("u_back_colour"),     surface.uniform("u_use_strain"),
          surface.uniform("u_strain_max"),      surface.uniform("u_eye"),
          surface.uniform("u_key_direction")};
    lu = {lines.uniform("u_view_projection"), lines.uniform("u_point_size"),
          lines.uniform("u_round_points")};
    legend_viewport = legend.uniform("u_viewport");
    glGenVertexArrays(kVaoCount, vao);
    // Attribute layouts are fixed once: buffers keep their names when they
    // grow, so the vertex arrays stay valid.
    for (const auto& [surface_vao, index] :
         {std::pair{cloth_vao, &triangles}, std::pair{coarse_vao, &coarse_triangles}}) {
      glBindVertexArray(vao[surface_vao]);  // the cloth's surface, whole or coarse
      vertex_attribute(vertex_slot::position, position, 3, 3, 0);
      vertex_attribute(vertex_slot::normal, normal, 3, 3, 0);
      vertex_attribute(vertex_slot::scalar, strain, 1, 1, 0);
      glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, index->id());
    }
    glBindVertexArray(vao[wire_vao]);
    vertex_attribute(vertex_slot::position, position, 3, 3, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, triangles.id());
    glBindVertexArray(vao[springs_vao]);
    vertex_attribute(vertex_slot::position, position, 3, 3, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, spring_pairs.id());
    glBindVertexArray(vao[nodes_vao]);
    vertex_attribute(vertex_slot::position, position, 3, 3, 0);
    vertex_attribute(vertex_slot::colour, node_colour, 4, 4, 0);
    glBindVertexArray(vao[collider_vao]);
    vertex_attribute(vertex_slot::position, collider_position, 3, 3, 0);
    vertex_attribute(vertex_slot::normal, collider_normal, 3, 3, 0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, collider_index.id());
    glBindVertexArray(vao[overlay_vao]);
    vertex_attribute(vertex_slot::position, overlay, 3, kOverlayFloats, 0);
    vertex_attribute(vertex_slot::colour, overlay, 4, kOverlayFloats, 3);
    glBindVertexArray(vao[ghost_vao]);
    vertex_attribute(vertex_slot::position, ghost, 3, 3, 0);
    glBindVertexArray(vao[legend_vao]);
    vertex_attribute(vertex_slot::position, legend_quad, 2, 3, 0);
    vertex_attribute(vertex_slot::scalar, legend_quad, 1, 3, 2);
    glBindVertexArray(0);
    glBindBuffer(GL_ARRAY_BUFFER, 0);
    check_gl("Renderer()");
  }

  ~Impl() { glDeleteVertexArrays(kVaoCount, vao); }

  long allocations() const {
    long n = 0;
    for (const GlBuffer* b :
         {&position, &normal, &strain, &triangles, &coarse_triangles, &spring_pairs, &node_colour,
          &collider_position, &collider_normal, &collider_index, &overlay, &legend_quad, &ghost})
      n += b->allocations();
    return n + grid.allocations();
  }

  void upload_geometry(const FrameSnapshot& s);
  void upload_frame(const FrameSnapshot& s, const RenderOptions& o);
  void use_surface(const OrbitCamera& camera, const Eigen::Matrix4f& vp, const RenderOptions& o);
  // The still part of a frame: the clear, the colliders, the ground grid.
  void draw_background(const OrbitCamera& camera, const Eigen::Matrix4f& vp,
                       const RenderOptions& o);
  void draw_cloth(const OrbitCamera& camera, const Eigen::Matrix4f& vp, const RenderOptions& o);
  void draw_lines(const Eigen::Matrix4f& vp, const FrameSnapshot& s, const RenderOptions& o,
                  int height);
  void draw_legend(const RenderOptions& o, int width, int height);
  void draw_ghosts(const Eigen::Matrix4f& vp, const std::vector<float>& points, int height);
};

void Renderer::Impl::upload_geometry(const FrameSnapshot& s) {
  geometry = s.geometry;
  triangle_indices = coarse_indices = 0;
  std::fill(std::begin(spring_begin), std::end(spring_begin), 0);
  const std::size_t n = geometry ? geometry->node_count : s.position.size() / 3;
  auto check = [&](std::int32_t i, const char* what) {
    if (i < 0 || std::size_t(i) >= n)
      throw std::invalid_argument(std::string("Renderer: a ") + what + " refers to node " +
                                  std::to_string(i) + " of " + std::to_string(n));
  };
  if (geometry) {
    for (const auto* list : {&geometry->triangles, &geometry->coarse_triangles})
      for (const auto& t : *list)
        for (const std::int32_t i : t)
          check(i, "triangle");
    triangles.upload(geometry->triangles);
    triangle_indices = 3 * geometry->triangles.size();
    coarse_triangles.upload(geometry->coarse_triangles);
    coarse_indices = 3 * geometry->coarse_triangles.size();
    // Springs grouped by family, so each family is one draw in its own colour.
    std::vector<std::uint32_t> pairs;
    pairs.reserve(2 * geometry->spring_a.size());
    for (int f = 0; f < kSpringFamilyCount; ++f) {
      spring_begin[f] = pairs.size();
      for (std::size_t k = 0; k < geometry->spring_a.size(); ++k)
        if (int(geometry->spring_family[k]) == f) {
          check(geometry->spring_a[k], "spring");
          check(geometry->spring_b[k], "spring");
          pairs.push_back(std::uint32_t(geometry->spring_a[k]));
          pairs.push_back(std::uint32_t(geometry->spring_b[k]));
        }
    }
    spring_begin[kSpringFamilyCount] = pairs.size();
    spring_pairs.upload(pairs);
  }
  grid.place(s);
  const GroundGrid& ground = grid.ground();
  const SurfaceMesh mesh = collider_mesh(geometry ? geometry->colliders : std::vector<ModuleSpec>(),
                                         ground.centre, kPlaneReach * ground.half_size());
  collider_position.upload(mesh.position);
  collider_normal.upload(mesh.normal);
  collider_index.upload(mesh.index);
  collider_indices = mesh.index.size();
  geometry_uploaded = true;
}

void Renderer::Impl::upload_frame(const FrameSnapshot& s, const RenderOptions& o) {
  const std::size_t n = s.position.size() / 3;
  if (geometry && (s.position.size() != 3 * geometry->node_count))
    throw std::invalid_argument("Renderer: the snapshot has " + std::to_string(s.position.size()) +
                                " coordinates for " + std::to_string(geometry->node_count) +
                                " nodes");
  shading.update(s, o.strain);
  position.upload(s.position);
  normal.upload(shading.normal);
  if (o.strain) strain.upload(shading.strain);
  if (o.nodes) {
    colours.resize(4 * n);
    for (std::size_t i = 0; i < n; ++i) {
      const bool pinned = i < s.pinned.size() && s.pinned[i];
      const palette::Colour& c = pinned ? palette::kNodePinned : palette::kNodeFree;
      std::copy(c.begin(), c.end(), colours.begin() + 4 * i);
      colours[4 * i + 3] = 1;
    }
    node_colour.upload(colours);
  }
}

void Renderer::Impl::use_surface(const OrbitCamera& camera, const Eigen::Matrix4f& vp,
                                 const RenderOptions& o) {
  surface.use();
  glUniformMatrix4fv(su.view_projection, 1, GL_FALSE, vp.data());
  const Vec3 eye = camera.eye();
  glUniform3f(su.eye, float(eye.x()), float(eye.y()), float(eye.z()));
  // The key light comes from above and to the left of the viewer, so whatever
  // the camera looks at is lit from the front.
  const Vec3 key =
      (-0.4 * camera.right() + 0.8 * camera.up() - 0.45 * camera.forward()).normalized();
  glUniform3f(su.key, float(key.x()), float(key.y()), float(key.z()));
  glUniform1f(su.strain_max, std::max(o.strain_max, 1e-6f));
}

void Renderer::Impl::draw_background(const OrbitCamera& camera, const Eigen::Matrix4f& vp,
                                     const RenderOptions& o) {
  const palette::Colour& bg = palette::kBackground;
  glClearColor(bg[0], bg[1], bg[2], 1);
  glClearDepth(1);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  if (o.colliders && collider_indices > 0) {
    use_surface(camera, vp, o);
    set_colour(su.front, palette::kCollider);
    set_colour(su.back, palette::kCollider);
    glUniform1i(su.use_strain, 0);
    glBindVertexArray(vao[collider_vao]);
    glVertexAttrib1f(vertex_slot::scalar, 0);
    // Pushed back a little so the grid lying on a floor plane is drawn over it.
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1, 1);
    glDrawElements(GL_TRIANGLES, GLsizei(collider_indices), GL_UNSIGNED_INT, nullptr);
    glDisable(GL_POLYGON_OFFSET_FILL);
  }
  // Blended over the colliders and the clear without writing depth, so it hides
  // nothing drawn later; the cloth, opaque, covers it where it is in front.
  if (o.grid) grid.draw(camera, vp);
}

void Renderer::Impl::draw_cloth(const OrbitCamera& camera, const Eigen::Matrix4f& vp,
                                const RenderOptions& o) {
  if (triangle_indices > 0) {
    use_surface(camera, vp, o);
    set_colour(su.front, palette::kClothFront);
    set_colour(su.back, palette::kClothBack);
    glUniform1i(su.use_strain, o.strain ? 1 : 0);
    const bool coarse = o.max_cloth_triangles > 0 && coarse_indices > 0 &&
                        triangle_indices / 3 > o.max_cloth_triangles;
    glBindVertexArray(vao[coarse ? coarse_vao : cloth_vao]);
    // The strain array is only filled when the map is on.
    if (o.strain)
      glEnableVertexAttribArray(vertex_slot::scalar);
    else
      glDisableVertexAttribArray(vertex_slot::scalar);
    // Lines drawn on the cloth (wireframe, springs, nodes) must win the depth test.
    const bool overlaid = o.wireframe || o.springs || o.nodes;
    if (overlaid) {
      glEnable(GL_POLYGON_OFFSET_FILL);
      glPolygonOffset(1, 2);
    } else {
      glDisable(GL_POLYGON_OFFSET_FILL);
    }
    glDrawElements(GL_TRIANGLES, GLsizei(coarse ? coarse_indices : triangle_indices),
                   GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_POLYGON_OFFSET_FILL);
}

void Renderer::Impl::draw_lines(const Eigen::Matrix4f& vp, const FrameSnapshot& s,
                                const RenderOptions& o, int height) {
  lines.use();
  glUniformMatrix4fv(lu.view_projection, 1, GL_FALSE, vp.data());
  glUniform1i(lu.round_points, 0);
  glEnable(GL_BLEND);
  // Colour blends; the framebuffer's alpha stays opaque for the PNG.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  if (o.wireframe && triangle_indices > 0) {
    glBindVertexArray(vao[wire_vao]);
    glVertexAttrib4f(vertex_slot::colour, palette::kWire[0], palette::kWire[1], palette::kWire[2],
                     0.55f);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawElements(GL_TRIANGLES, GLsizei(triangle_indices), GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  if (o.springs && spring_begin[kSpringFamilyCount] > 0) {
    glBindVertexArray(vao[springs_vao]);
    for (int f = 0; f < kSpringFamilyCount; ++f) {
      const palette::Colour& c = palette::kSpring[f];
      glVertexAttrib4f(vertex_slot::colour, c[0], c[1], c[2], 0.9f);
      const std::size_t count = spring_begin[f + 1] - spring_begin[f];
      if (count > 0)
        glDrawElements(GL_LINES, GLsizei(count), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(spring_begin[f] * sizeof(std::uint32_t)));
    }
  }
  const float point_size = std::clamp(float(height) / 180.0f, 3.0f, 10.0f);
  if (o.nodes && !s.position.empty()) {
    glUniform1f(lu.point_size, point_size);
    glUniform1i(lu.round_points, 1);
    glBindVertexArray(vao[nodes_vao]);
    glDrawArrays(GL_POINTS, 0, GLsizei(s.position.size() / 3));
    glUniform1i(lu.round_points, 0);
  }
  // Applied forces: a line from the node to where it is pulled, drawn over
  // everything so a drag stays visible behind the cloth.
  if (o.forces && !s.forces.empty()) {
    overlay_data.clear();
    const palette::Colour& c = palette::kForce;
    for (const FrameSnapshot::AppliedForce& f : s.forces) {
      if (f.node < 0 || std::size_t(f.node) >= s.position.size() / 3) continue;
      const Vec3 a = s.node(std::size_t(f.node));
      overlay_data.insert(overlay_data.end(), {float(a.x()), float(a.y()), float(a.z()), c[0], c[1],
                                               c[2], 1.0f, float(f.anchor.x()), float(f.anchor.y()),
                                               float(f.anchor.z()), c[0], c[1], c[2], 1.0f});
    }
    if (!overlay_data.empty()) {
      overlay.upload(overlay_data);
      glDisable(GL_DEPTH_TEST);
      glBindVertexArray(vao[overlay_vao]);
      const GLsizei count = GLsizei(overlay_data.size() / kOverlayFloats);
      glDrawArrays(GL_LINES, 0, count);
      glUniform1f(lu.point_size, point_size + 2);
      glUniform1i(lu.round_points, 1);
      glDrawArrays(GL_POINTS, 0, count);
      glUniform1i(lu.round_points, 0);
      glEnable(GL_DEPTH_TEST);
    }
  }
  glDisable(GL_BLEND);
}

// The reference's points, over everything (a ghost behind the cloth stays
// visible), a little smaller than the nodes so both show where they meet.
void Renderer::Impl::draw_ghosts(const Eigen::Matrix4f& vp, const std::vector<float>& points,
                                 int height) {
  if (points.size() < 3) return;
  ghost.upload(points);
  lines.use();
  glUniformMatrix4fv(lu.view_projection, 1, GL_FALSE, vp.data());
  glUniform1f(lu.point_size, std::clamp(float(height) / 240.0f, 3.0f, 8.0f));
  glUniform1i(lu.round_points, 1);
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(vao[ghost_vao]);
  const palette::Colour& c = palette::kGhost;
  glVertexAttrib4f(vertex_slot::colour, c[0], c[1], c[2], 1.0f);
  glDrawArrays(GL_POINTS, 0, GLsizei(points.size() / 3));
  glUniform1i(lu.round_points, 0);
  glEnable(GL_DEPTH_TEST);
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
  overlay_data.clear();
  const palette::Colour& c = palette::kLegendText;
  for (std::size_t i = 0; i + 1 < segments.size(); i += 2)
    overlay_data.insert(overlay_data.end(), {segments[i], segments[i + 1], 0, c[0], c[1], c[2], 1});
  overlay.upload(overlay_data);
  lines.use();
  const Eigen::Matrix4f pixels = pixel_projection(width, height);
  glUniformMatrix4fv(lu.view_projection, 1, GL_FALSE, pixels.data());
  glBindVertexArray(vao[overlay_vao]);
  glDrawArrays(GL_LINES, 0, GLsizei(overlay_data.size() / kOverlayFloats));
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
  m.draw_cloth(camera, vp, options);
  m.draw_lines(vp, snapshot, options, height);
  if (ghost_points) m.draw_ghosts(vp, *ghost_points, height);
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
