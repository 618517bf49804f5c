#include "render/ground_grid.h"

#include <algorithm>
#include <cmath>

#include "render/snapshot_framing.h"

namespace neurocloth {

GroundGrid place_ground_grid(const FrameSnapshot& snapshot) {
  GroundGrid g;
  const Bounds b = snapshot_bounds(snapshot);
  double y = b.empty() ? 0.0 : std::min(0.0, b.lo.y());
  bool floor_found = false;
  if (snapshot.geometry)
    for (std::size_t i = 0; i < snapshot.geometry->colliders.size(); ++i)
      if (const auto* p = std::get_if<PlaneSpec>(&snapshot.geometry->colliders[i])) {
        const RigidPose pose = snapshot_collider_pose(snapshot, i);
        if ((pose.rotation * p->normal).normalized().y() > 0.99) {  // a floor: the grid lies on it
          const double height = pose.apply(p->point).y();
          y = floor_found ? std::max(y, height) : height;
          floor_found = true;
        }
      }
  // Cells about a tenth of the scene's size, a power of ten (0.1 m for a
  // cloth of one to three metres), over a square eight times the scene's size
  // so that the grid reaches the horizon of a framed view before it fades.
  const double size = b.empty() ? 1.0 : std::max((b.hi - b.lo).maxCoeff(), 1e-3);
  g.cell = std::pow(10.0, std::round(std::log10(size)) - 1);
  g.cells = 20 * std::clamp(int(std::ceil(8 * size / g.cell / 20)), 1, 20);
  const double x = b.empty() ? 0.0 : 0.5 * (b.lo.x() + b.hi.x());
  const double z = b.empty() ? 0.0 : 0.5 * (b.lo.z() + b.hi.z());
  // Centred under the scene on a multiple of ten cells, so major lines stay on round numbers.
  const double major = 10 * g.cell;
  g.centre = Vec3(major * std::round(x / major), y, major * std::round(z / major));
  return g;
}

std::vector<float> ground_grid_square(const GroundGrid& g) {
  const float h = float(g.half_size());
  const float x = float(g.centre.x()), y = float(g.centre.y()), z = float(g.centre.z());
  return {x - h, y, z - h, x + h, y, z - h, x - h, y, z + h, x + h, y, z + h};
}

}  // namespace neurocloth
