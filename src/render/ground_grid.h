#pragma once
// The ground grid under the scene (plain C++, no OpenGL): where it lies and
// the lines it is made of. It is placed once per scene, not every frame, so it
// does not jump while the cloth moves.
#include <vector>

#include "frame_snapshot.h"

namespace neurocloth {

struct GroundGrid {
  Vec3 centre = Vec3::Zero();  // on the grid's plane (y = centre.y)
  double cell = 0.1;           // m between lines; every tenth line is darker
  int cells = 100;             // across the whole grid, a multiple of 20
  double half_size() const { return 0.5 * cell * cells; }
};

// At y = 0, or lower when something of the scene reaches below 0, or at the
// height of a horizontal plane collider (the floor); cells sized to the scene.
GroundGrid place_ground_grid(const FrameSnapshot& snapshot);

// The grid's lines as strips to draw them on (shaders/grid.vert widens each
// strip to the few pixels around its line, grid.frag draws the line in it per
// pixel). Filling the whole square instead cost about 7 ms of llvmpipe's time
// a frame at 1280 x 720, mostly pixels far from any line (docs/rendering.md).
// Every line at a cell boundary, in both directions, cut into segments of
// `cells_per_segment` cells: per vertex the point on the line (x, y, z) and
// the unit direction across it in the grid's plane, signed for the strip's
// side (x, y, z); two triangles a segment, no index.
inline constexpr int kGridFloatsPerVertex = 6;
std::vector<float> ground_grid_strips(const GroundGrid& grid, int cells_per_segment);

}  // namespace neurocloth
