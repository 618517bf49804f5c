#pragma once
// The colliders on the GPU, in two parts. The still ones (every collider that
// neither moves nor deforms) are one mesh in world coordinates, built and
// uploaded once a scene and drawn with the frame's still part (the background
// copy, background_cache.h). The moving ones keep their meshes in their shape
// frames (collider_tessellation.h), built once a scene, and every frame are
// placed at the snapshot's poses (a deforming mesh at its vertices, its normals
// recomputed) into buffers rewritten in place, drawn each frame after the
// still part.
#include <GL/glew.h>

#include <Eigen/Core>
#include <vector>

#include "core/scene/collider_tessellation.h"
#include "core/scene/frame_snapshot.h"
#include "render/gl_buffer.h"
#include "render/orbit_camera.h"
#include "render/surface_program.h"

namespace neurocloth {

class ColliderLayer {
 public:
  ColliderLayer();
  ~ColliderLayer();
  ColliderLayer(const ColliderLayer&) = delete;
  ColliderLayer& operator=(const ColliderLayer&) = delete;

  // `geometry`'s colliders (none when null); planes as squares of half side
  // `plane_half_size` around `centre`. A still collider rotated by its
  // declaration (an oriented box) is placed here, at its pose at `time`.
  void upload_geometry(const SceneGeometry* geometry, const Vec3& centre, double plane_half_size,
                       double time);
  // The moving colliders where `snapshot` has them (its placements; a
  // snapshot without them, at collider_pose of its time). Its geometry must be
  // the one uploaded.
  void upload_frame(const FrameSnapshot& snapshot);
  void draw_still(const SurfaceProgram& surface, const OrbitCamera& camera,
                  const Eigen::Matrix4f& view_projection, float strain_max) const;
  void draw_moving(const SurfaceProgram& surface, const OrbitCamera& camera,
                   const Eigen::Matrix4f& view_projection, float strain_max) const;
  bool has_moving() const { return !moving_.empty(); }

  long allocations() const;

 private:
  // One moving collider: which of the geometry's, its mesh in its shape frame,
  // and where its vertices go in the moving buffers.
  struct Moving {
    std::size_t collider = 0;
    SurfaceMesh shape;
    std::size_t first_vertex = 0;
    bool deforms = false;
    SurfaceMesh placed;  // a deforming one's scratch: its vertices at the frame
  };

  enum Vao { still_vao, moving_vao, kVaoCount };
  GLuint vao_[kVaoCount] = {};
  GlBuffer still_position_, still_normal_, still_index_;
  GlBuffer moving_position_, moving_normal_, moving_index_;
  std::size_t still_indices_ = 0, moving_indices_ = 0;
  std::vector<Moving> moving_;
  std::vector<float> position_, normal_;  // the moving colliders' frame, kept for its storage
};

}  // namespace neurocloth
