#pragma once
// The lit surface program (shaders/surface.*): two-sided, front and back in
// their own colours, lit by a key light that follows the camera, and coloured
// by strain when asked. The cloth (cloth_layer.h) and the colliders are drawn
// with it.
#include <GL/glew.h>

#include <Eigen/Core>
#include <string>

#include "render/gl_program.h"
#include "render/orbit_camera.h"
#include "render/render_palette.h"

namespace neurocloth {

class SurfaceProgram {
 public:
  explicit SurfaceProgram(const std::string& shader_dir);

  // Uses the program as seen from `camera`, with the two sides' colours; the
  // strain map is on when `strain`, red at `strain_max`.
  void use(const OrbitCamera& camera, const Eigen::Matrix4f& view_projection, float strain_max,
           const palette::Colour& front, const palette::Colour& back, bool strain) const;

 private:
  GlProgram program_;
  struct {
    GLint view_projection, front, back, use_strain, strain_max, eye, key;
  } u_;
};

}  // namespace neurocloth
