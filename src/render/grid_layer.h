#pragma once
// The ground grid's GL side: its program, its strips' buffer and vertex array,
// where it lies (ground_grid.h places it), and its draw. The lines are drawn
// per pixel on one square (shaders/grid.frag).
#include <GL/glew.h>

#include <Eigen/Core>
#include <string>

#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/ground_grid.h"
#include "render/orbit_camera.h"

namespace neurocloth {

class GridLayer {
 public:
  explicit GridLayer(const std::string& shader_dir);
  ~GridLayer();
  GridLayer(const GridLayer&) = delete;
  GridLayer& operator=(const GridLayer&) = delete;

  // Places the grid under the snapshot's scene and uploads its square.
  void place(const FrameSnapshot& snapshot);
  const GroundGrid& ground() const { return ground_; }

  // Blended over what is drawn, without writing depth, so it hides nothing;
  // leaves blending off.
  void draw(const OrbitCamera& camera, const Eigen::Matrix4f& view_projection) const;

  long allocations() const { return square_.allocations(); }

 private:
  GlProgram program_;
  struct {
    GLint view_projection, cell, origin, minor, major, fade_centre, fade_radius;
  } u_;
  GLuint vao_ = 0;
  GlBuffer square_;
  GroundGrid ground_;
};

}  // namespace neurocloth
