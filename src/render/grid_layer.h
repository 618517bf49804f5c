#pragma once
// The ground grid's GL side: its program, its strips' buffer and vertex array,
// where it lies (ground_grid.h places it), and its draw. The lines are drawn
// per pixel on strips around them (shaders/grid.vert, grid.frag).
#include <GL/glew.h>

#include <Eigen/Core>
#include <string>

#include "gl_buffer.h"
#include "gl_program.h"
#include "ground_grid.h"
#include "orbit_camera.h"

namespace neurocloth {

class GridLayer {
 public:
  explicit GridLayer(const std::string& shader_dir);
  ~GridLayer();
  GridLayer(const GridLayer&) = delete;
  GridLayer& operator=(const GridLayer&) = delete;

  // Places the grid under the snapshot's scene and uploads its strips.
  void place(const FrameSnapshot& snapshot);
  const GroundGrid& ground() const { return ground_; }

  // Blended over what is drawn, without writing depth, so it hides nothing;
  // leaves blending and the stencil test off.
  void draw(const OrbitCamera& camera, const Eigen::Matrix4f& view_projection, int width,
            int height) const;

  long allocations() const { return strips_.allocations(); }

 private:
  GlProgram program_;
  struct {
    GLint view_projection, cell, origin, minor, major, fade_centre, fade_radius, viewport,
        max_half_width;
  } u_;
  GLuint vao_ = 0;
  GlBuffer strips_;
  std::size_t vertices_ = 0;
  GroundGrid ground_;
};

}  // namespace neurocloth
