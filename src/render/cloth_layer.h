#pragma once
// The cloth's surface on the GPU: its nodes' positions, normals and strain,
// rewritten every frame, and its triangles, whole and coarse, uploaded once a
// scene; drawn with the surface program. The line layer (line_layer.h) draws
// the wireframe, the springs and the nodes from the same positions.
#include <GL/glew.h>

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>

#include "core/scene/frame_snapshot.h"
#include "render/cloth_shading.h"
#include "render/gl_buffer.h"
#include "render/orbit_camera.h"
#include "render/renderer.h"
#include "render/surface_program.h"

namespace neurocloth {

// Throws std::invalid_argument unless `i` is one of the scene's `nodes`: an
// index past them would have the GL read outside the position buffer. `what`
// names what refers to it, for the message.
void check_node_index(std::int32_t i, std::size_t nodes, const char* what);

class ClothLayer {
 public:
  ClothLayer();
  ~ClothLayer();
  ClothLayer(const ClothLayer&) = delete;
  ClothLayer& operator=(const ClothLayer&) = delete;

  // Draws nothing until the next upload_geometry.
  void forget_geometry();
  // Checks the triangles' nodes (throws naming the first bad one), then uploads them.
  void upload_geometry(const SceneGeometry& geometry);
  // The frame's positions and normals, and its strain when `strain`.
  void upload_frame(const FrameSnapshot& snapshot, bool strain);
  // Opaque; pushed back in depth when lines are drawn over it.
  void draw(const SurfaceProgram& surface, const OrbitCamera& camera,
            const Eigen::Matrix4f& view_projection, const RenderOptions& options) const;

  // What the line layer draws from.
  const GlBuffer& position() const { return position_; }
  const GlBuffer& triangles() const { return triangles_; }
  std::size_t triangle_indices() const { return triangle_indices_; }

  long allocations() const;

 private:
  enum Vao { whole_vao, coarse_vao, kVaoCount };
  GLuint vao_[kVaoCount] = {};
  GlBuffer position_, normal_, strain_, triangles_, coarse_triangles_;
  std::size_t triangle_indices_ = 0, coarse_indices_ = 0;
  ClothShading shading_;  // per-frame scratch, kept for its storage
};

}  // namespace neurocloth
