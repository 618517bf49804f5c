#pragma once
// Where each node would go in one step with no spring acting: the target the
// large steps' minimisations (projective, vertex block descent) pull towards.
#include <cstddef>
#include <vector>

#include "core/network/cloth_network.h"

namespace neurocloth {

// y - x0 = h v0 + h^2 M^-1 (f_other + m g) on free nodes, h v0 on pinned ones,
// planar (every node's x, then y, then z). f_other, the forces that are not
// springs (the external force, the scene's air and wind), is evaluated at the
// start of the step into `other_force`.
inline void inertial_displacement(const ClothNetwork& net, const ForceInputs& inputs,
                                  const ForceContext& context, const ClothState& in, double h,
                                  NodeVectors& other_force, std::vector<double>& y) {
  const std::size_t n = net.node_count();
  net.other_forces(in, inputs, context, other_force);
  const double* const v[3] = {in.vx.data(), in.vy.data(), in.vz.data()};
  const double* const f[3] = {other_force.x.data(), other_force.y.data(), other_force.z.data()};
  const double g[3] = {net.gravity.x(), net.gravity.y(), net.gravity.z()};
  y.resize(3 * n);
  for (std::size_t c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < n; ++i) {
      const double free = net.masses.free[i], w = net.masses.inverse_mass[i];
      y[c * n + i] = h * v[c][i] + free * h * h * (w * f[c][i] + g[c]);
    }
}

}  // namespace neurocloth
