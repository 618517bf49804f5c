#include "ground_grid.h"

#include <algorithm>
#include <cmath>

#include "snapshot_framing.h"

namespace neurocloth {

GroundGrid place_ground_grid(const FrameSnapshot& snapshot) {
  GroundGrid g;
  const Bounds b = snapshot_bounds(snapshot);
  double y = b.empty() ? 0.0 : std::min(0.0, b.lo.y());
  bool floor_found = false;
  if (snapshot.geometry)
    for (const ModuleSpec& spec : snapshot.geometry->colliders)
      if (const auto* p = std::get_if<PlaneSpec>(&spec))
        if (p->normal.normalized().y() > 0.99) {  // a floor: the grid lies on it
          y = floor_found ? std::max(y, p->point.y()) : p->point.y();
          floor_found = true;
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

std::vector<float> ground_grid_strips(const GroundGrid& g, int cells_per_segment) {
  const int per = std::clamp(cells_per_segment, 1, std::max(g.cells, 1));
  const int segments = (g.cells + per - 1) / per;
  std::vector<float> v;
  v.reserve(std::size_t(2) * (g.cells + 1) * segments * 6 * kGridFloatsPerVertex);
  const double h = g.half_size();
  // Lines along x (at fixed z), then along z (at fixed x): `across` is the
  // axis a line's position is fixed on.
  for (int across : {2, 0}) {
    const int along = 2 - across;
    for (int line = 0; line <= g.cells; ++line) {
      const double at = -h + line * g.cell;
      for (int k = 0; k < segments; ++k) {
        const double from = -h + k * per * g.cell;
        const double to = -h + std::min((k + 1) * per, g.cells) * g.cell;
        auto vertex = [&](double t, float side) {
          Vec3 p = g.centre;
          p[across] += at;
          p[along] += t;
          for (int i = 0; i < 3; ++i)
            v.push_back(float(p[i]));
          for (int i = 0; i < 3; ++i)
            v.push_back(i == across ? side : 0.0f);
        };
        // Two triangles: (from, -) (to, -) (from, +) and (from, +) (to, -) (to, +).
        vertex(from, -1), vertex(to, -1), vertex(from, 1);
        vertex(from, 1), vertex(to, -1), vertex(to, 1);
      }
    }
  }
  return v;
}

}  // namespace neurocloth
