#pragma once
// What the renderer derives from a snapshot every frame, in plain C++ (no
// OpenGL, testable): smooth vertex normals and the strain at each vertex.
// The vectors are members so that frames of one size reuse their storage.
#include <vector>

#include "core/scene/frame_snapshot.h"

namespace neurocloth {

struct ClothShading {
  std::vector<float> normal;  // x, y, z per node: the area-weighted sum of its
                              // triangles' normals, unit; +y for a node in no triangle
  // Per node: the mean stretch len/rest - 1 of its in-plane springs (structural
  // and shear; bend springs shorten whenever the cloth folds and would paint
  // every fold as compressed). A cloth with no in-plane springs uses all.
  std::vector<float> strain;

  // Recomputes the normals, and the strain when `with_strain`.
  void update(const FrameSnapshot& snapshot, bool with_strain);

 private:
  std::vector<float> spring_count_;  // per node, scratch for the strain average
};

}  // namespace neurocloth
