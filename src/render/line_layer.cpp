#include "render/line_layer.h"

#include <algorithm>
#include <cstdint>

namespace neurocloth {
namespace {

constexpr int kOverlayFloats = 7;  // x, y, z, r, g, b, a

// Maps pixels (origin top left, y down) to clip space, for the 2D legend.
Eigen::Matrix4f pixel_projection(int width, int height) {
  Eigen::Matrix4f m = Eigen::Matrix4f::Identity();
  m(0, 0) = 2.0f / float(width);
  m(0, 3) = -1;
  m(1, 1) = -2.0f / float(height);
  m(1, 3) = 1;
  return m;
}

}  // namespace

LineLayer::LineLayer(const std::string& shader_dir, const ClothLayer& cloth)
    : cloth_(cloth), program_(shader_dir, "lines.vert", "lines.frag") {
  u_ = {program_.uniform("u_view_projection"), program_.uniform("u_point_size"),
        program_.uniform("u_round_points")};
  glGenVertexArrays(kVaoCount, vao_);
  // Attribute layouts are fixed once: buffers keep their names when they
  // grow, so the vertex arrays stay valid.
  glBindVertexArray(vao_[wire_vao]);
  vertex_attribute(vertex_slot::position, cloth_.position(), 3, 3, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, cloth_.triangles().id());
  glBindVertexArray(vao_[springs_vao]);
  vertex_attribute(vertex_slot::position, cloth_.position(), 3, 3, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, spring_pairs_.id());
  glBindVertexArray(vao_[nodes_vao]);
  vertex_attribute(vertex_slot::position, cloth_.position(), 3, 3, 0);
  vertex_attribute(vertex_slot::colour, node_colour_, 4, 4, 0);
  glBindVertexArray(vao_[overlay_vao]);
  vertex_attribute(vertex_slot::position, overlay_, 3, kOverlayFloats, 0);
  vertex_attribute(vertex_slot::colour, overlay_, 4, kOverlayFloats, 3);
  glBindVertexArray(vao_[ghost_vao]);
  vertex_attribute(vertex_slot::position, ghost_, 3, 3, 0);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

LineLayer::~LineLayer() {
  glDeleteVertexArrays(kVaoCount, vao_);
}

long LineLayer::allocations() const {
  long n = 0;
  for (const GlBuffer* b : {&spring_pairs_, &node_colour_, &overlay_, &ghost_})
    n += b->allocations();
  return n;
}

void LineLayer::forget_geometry() {
  std::fill(std::begin(spring_begin_), std::end(spring_begin_), 0);
}

void LineLayer::upload_geometry(const SceneGeometry& geometry) {
  std::vector<std::uint32_t> pairs;
  pairs.reserve(2 * geometry.spring_a.size());
  for (int f = 0; f < kSpringFamilyCount; ++f) {
    spring_begin_[f] = pairs.size();
    for (std::size_t k = 0; k < geometry.spring_a.size(); ++k)
      if (int(geometry.spring_family[k]) == f) {
        check_node_index(geometry.spring_a[k], geometry.node_count, "spring");
        check_node_index(geometry.spring_b[k], geometry.node_count, "spring");
        pairs.push_back(std::uint32_t(geometry.spring_a[k]));
        pairs.push_back(std::uint32_t(geometry.spring_b[k]));
      }
  }
  spring_begin_[kSpringFamilyCount] = pairs.size();
  spring_pairs_.upload(pairs);
}

void LineLayer::upload_frame(const FrameSnapshot& s, bool nodes) {
  if (!nodes) return;
  const std::size_t n = s.position.size() / 3;
  colours_.resize(4 * n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool pinned = i < s.pinned.size() && s.pinned[i];
    const palette::Colour& c = pinned ? palette::kNodePinned : palette::kNodeFree;
    std::copy(c.begin(), c.end(), colours_.begin() + 4 * i);
    colours_[4 * i + 3] = 1;
  }
  node_colour_.upload(colours_);
}

void LineLayer::draw(const Eigen::Matrix4f& vp, const FrameSnapshot& s, const RenderOptions& o,
                     int height) {
  program_.use();
  glUniformMatrix4fv(u_.view_projection, 1, GL_FALSE, vp.data());
  glUniform1i(u_.round_points, 0);
  glEnable(GL_BLEND);
  // Colour blends; the framebuffer's alpha stays opaque for the PNG.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  const std::size_t triangle_indices = cloth_.triangle_indices();
  if (o.wireframe && triangle_indices > 0) {
    glBindVertexArray(vao_[wire_vao]);
    glVertexAttrib4f(vertex_slot::colour, palette::kWire[0], palette::kWire[1], palette::kWire[2],
                     0.55f);
    glPolygonMode(GL_FRONT_AND_BACK, GL_LINE);
    glDrawElements(GL_TRIANGLES, GLsizei(triangle_indices), GL_UNSIGNED_INT, nullptr);
    glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
  }
  if (o.springs && spring_begin_[kSpringFamilyCount] > 0) {
    glBindVertexArray(vao_[springs_vao]);
    for (int f = 0; f < kSpringFamilyCount; ++f) {
      const palette::Colour& c = palette::kSpring[f];
      glVertexAttrib4f(vertex_slot::colour, c[0], c[1], c[2], 0.9f);
      const std::size_t count = spring_begin_[f + 1] - spring_begin_[f];
      if (count > 0)
        glDrawElements(GL_LINES, GLsizei(count), GL_UNSIGNED_INT,
                       reinterpret_cast<const void*>(spring_begin_[f] * sizeof(std::uint32_t)));
    }
  }
  const float point_size = std::clamp(float(height) / 180.0f, 3.0f, 10.0f);
  if (o.nodes && !s.position.empty()) {
    glUniform1f(u_.point_size, point_size);
    glUniform1i(u_.round_points, 1);
    glBindVertexArray(vao_[nodes_vao]);
    glDrawArrays(GL_POINTS, 0, GLsizei(s.position.size() / 3));
    glUniform1i(u_.round_points, 0);
  }
  // Applied forces: a line from the node to where it is pulled, drawn over
  // everything so a drag stays visible behind the cloth.
  if (o.forces && !s.forces.empty()) {
    overlay_data_.clear();
    const palette::Colour& c = palette::kForce;
    for (const FrameSnapshot::AppliedForce& f : s.forces) {
      if (f.node < 0 || std::size_t(f.node) >= s.position.size() / 3) continue;
      const Vec3 a = s.node(std::size_t(f.node));
      overlay_data_.insert(
          overlay_data_.end(),
          {float(a.x()), float(a.y()), float(a.z()), c[0], c[1], c[2], 1.0f, float(f.anchor.x()),
           float(f.anchor.y()), float(f.anchor.z()), c[0], c[1], c[2], 1.0f});
    }
    if (!overlay_data_.empty()) {
      overlay_.upload(overlay_data_);
      glDisable(GL_DEPTH_TEST);
      glBindVertexArray(vao_[overlay_vao]);
      const GLsizei count = GLsizei(overlay_data_.size() / kOverlayFloats);
      glDrawArrays(GL_LINES, 0, count);
      glUniform1f(u_.point_size, point_size + 2);
      glUniform1i(u_.round_points, 1);
      glDrawArrays(GL_POINTS, 0, count);
      glUniform1i(u_.round_points, 0);
      glEnable(GL_DEPTH_TEST);
    }
  }
  glDisable(GL_BLEND);
}

// The reference's points, over everything (a ghost behind the cloth stays
// visible), a little smaller than the nodes so both show where they meet.
void LineLayer::draw_ghosts(const Eigen::Matrix4f& vp, const std::vector<float>& points,
                            int height) {
  if (points.size() < 3) return;
  ghost_.upload(points);
  program_.use();
  glUniformMatrix4fv(u_.view_projection, 1, GL_FALSE, vp.data());
  glUniform1f(u_.point_size, std::clamp(float(height) / 240.0f, 3.0f, 8.0f));
  glUniform1i(u_.round_points, 1);
  glDisable(GL_DEPTH_TEST);
  glBindVertexArray(vao_[ghost_vao]);
  const palette::Colour& c = palette::kGhost;
  glVertexAttrib4f(vertex_slot::colour, c[0], c[1], c[2], 1.0f);
  glDrawArrays(GL_POINTS, 0, GLsizei(points.size() / 3));
  glUniform1i(u_.round_points, 0);
  glEnable(GL_DEPTH_TEST);
}

void LineLayer::draw_in_pixels(const std::vector<float>& segments, const palette::Colour& c,
                               int width, int height) {
  overlay_data_.clear();
  for (std::size_t i = 0; i + 1 < segments.size(); i += 2)
    overlay_data_.insert(overlay_data_.end(),
                         {segments[i], segments[i + 1], 0, c[0], c[1], c[2], 1});
  overlay_.upload(overlay_data_);
  program_.use();
  const Eigen::Matrix4f pixels = pixel_projection(width, height);
  glUniformMatrix4fv(u_.view_projection, 1, GL_FALSE, pixels.data());
  glBindVertexArray(vao_[overlay_vao]);
  glDrawArrays(GL_LINES, 0, GLsizei(overlay_data_.size() / kOverlayFloats));
}

}  // namespace neurocloth
