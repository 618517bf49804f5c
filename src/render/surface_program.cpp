#include "render/surface_program.h"

#include <algorithm>

namespace neurocloth {

SurfaceProgram::SurfaceProgram(const std::string& shader_dir)
    : program_(shader_dir, "surface.vert", "surface.frag", {"strain_colour.glsl"}) {
  u_ = {program_.uniform("u_view_projection"), program_.uniform("u_front_colour"),
        program_.uniform("u_back_colour"),     program_.uniform("u_use_strain"),
        program_.uniform("u_strain_max"),      program_.uniform("u_eye"),
        program_.uniform("u_key_direction")};
}

void SurfaceProgram::use(const OrbitCamera& camera, const Eigen::Matrix4f& vp, float strain_max,
                         const palette::Colour& front, const palette::Colour& back,
                         bool strain) const {
  program_.use();
  glUniformMatrix4fv(u_.view_projection, 1, GL_FALSE, vp.data());
  const Vec3 eye = camera.eye();
  glUniform3f(u_.eye, float(eye.x()), float(eye.y()), float(eye.z()));
  // The key light comes from above and to the left of the viewer, so whatever
  // the camera looks at is lit from the front.
  const Vec3 key =
      (-0.4 * camera.right() + 0.8 * camera.up() - 0.45 * camera.forward()).normalized();
  glUniform3f(u_.key, float(key.x()), float(key.y()), float(key.z()));
  glUniform1f(u_.strain_max, std::max(strain_max, 1e-6f));
  set_colour(u_.front, front);
  set_colour(u_.back, back);
  glUniform1i(u_.use_strain, strain ? 1 : 0);
}

}  // namespace neurocloth
