#include "render/grid_layer.h"

#include <vector>

#include "render/gl_program.h"
#include "render/render_palette.h"

namespace neurocloth {
GridLayer::GridLayer(const std::string& shader_dir)
    : program_(shader_dir, "grid.vert", "grid.frag") {
  u_ = {program_.uniform("u_view_projection"), program_.uniform("u_cell"),
        program_.uniform("u_origin"),          program_.uniform("u_minor_colour"),
        program_.uniform("u_major_colour"),    program_.uniform("u_fade_centre"),
        program_.uniform("u_fade_radius")};
  glGenVertexArrays(1, &vao_);
  glBindVertexArray(vao_);
  vertex_attribute(vertex_slot::position, square_, 3, 3, 0);
  glBindVertexArray(0);
  glBindBuffer(GL_ARRAY_BUFFER, 0);
}

GridLayer::~GridLayer() {
  glDeleteVertexArrays(1, &vao_);
}

void GridLayer::place(const FrameSnapshot& snapshot) {
  ground_ = place_ground_grid(snapshot);
  square_.upload(ground_grid_square(ground_));
}

void GridLayer::draw(const OrbitCamera& camera, const Eigen::Matrix4f& vp) const {
  program_.use();
  glUniformMatrix4fv(u_.view_projection, 1, GL_FALSE, vp.data());
  glUniform1f(u_.cell, float(ground_.cell));
  glUniform3f(u_.origin, float(ground_.centre.x()), float(ground_.centre.y()),
              float(ground_.centre.z()));
  set_colour(u_.minor, palette::kGridMinor);
  set_colour(u_.major, palette::kGridMajor);
  // The grid fades out around the point the camera circles.
  glUniform3f(u_.fade_centre, float(camera.target.x()), float(camera.target.y()),
              float(camera.target.z()));
  glUniform1f(u_.fade_radius, float(ground_.half_size()));
  glEnable(GL_BLEND);
  // Colour blends; the framebuffer's alpha stays opaque for the PNG.
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
  glDepthMask(GL_FALSE);
  glBindVertexArray(vao_);
  glDrawArrays(GL_TRIANGLE_STRIP, 0, 4);
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
}

}  // namespace neurocloth
