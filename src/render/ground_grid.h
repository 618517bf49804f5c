#pragma once
// The ground grid under the scene (plain C++, no OpenGL): where it lies and
// the lines it is made of. It is placed once per scene, not every frame, so it
// does not jump while the cloth moves.
#include <vector>

#include "core/scene/frame_snapshot.h"

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

// The grid's square as x, y, z of four corners in triangle-strip order; the
// lines are drawn on it per pixel (shaders/grid.frag).
std::vector<float> ground_grid_square(const GroundGrid& grid);

}  // namespace neurocloth
