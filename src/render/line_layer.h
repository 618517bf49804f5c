#pragma once
// Everything drawn with the lines program (shaders/lines.*): over the cloth,
// its wireframe, its springs coloured by family, its nodes (the pinned ones
// red) and the applied forces; the reference's ghost points; and segments in
// pixels, for the strain legend's frame and labels. The cloth's lines read the
// cloth layer's positions, so this layer lives no longer than that one.
#include <GL/glew.h>

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "core/scene/frame_snapshot.h"
#include "render/cloth_layer.h"
#include "render/gl_buffer.h"
#include "render/gl_program.h"
#include "render/render_palette.h"
#include "render/renderer.h"

namespace neurocloth {

class LineLayer {
 public:
  LineLayer(const std::string& shader_dir, const ClothLayer& cloth);
  ~LineLayer();
  LineLayer(const LineLayer&) = delete;
  LineLayer& operator=(const LineLayer&) = delete;

  // Draws no springs until the next upload_geometry.
  void forget_geometry();
  // Checks the springs' nodes (throws naming the first bad one), then uploads
  // them grouped by family, so each family is one draw in its own colour.
  void upload_geometry(const SceneGeometry& geometry);
  // The nodes' colours, when `nodes` are drawn.
  void upload_frame(const FrameSnapshot& snapshot, bool nodes);

  // The wireframe, springs, nodes and forces `options` asks for, blended;
  // points are sized for a frame `height` pixels tall. Leaves blending off.
  void draw(const Eigen::Matrix4f& view_projection, const FrameSnapshot& snapshot,
            const RenderOptions& options, int height);
  // `points` (x, y, z each) as discs over everything.
  void draw_ghosts(const Eigen::Matrix4f& view_projection, const std::vector<float>& points,
                   int height);
  // `segments` (x0, y0, x1, y1 in pixels, origin top left, y down) in one colour
  // on a `width` x `height` frame.
  void draw_in_pixels(const std::vector<float>& segments, const palette::Colour& colour, int width,
                      int height);

  long allocations() const;

 private:
  const ClothLayer& cloth_;
  GlProgram program_;
  struct {
    GLint view_projection, point_size, round_points;
  } u_;
  enum Vao { wire_vao, springs_vao, nodes_vao, overlay_vao, ghost_vao, kVaoCount };
  GLuint vao_[kVaoCount] = {};
  GlBuffer spring_pairs_, node_colour_, overlay_, ghost_;
  std::size_t spring_begin_[kSpringFamilyCount + 1] = {};  // index ranges by family
  std::vector<float> colours_, overlay_data_;  // per-frame scratch, kept for its storage
};

}  // namespace neurocloth
