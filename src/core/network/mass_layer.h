#pragma once
// The paper's mass layer (section 3). Per node j:
//   acceleration neuron  net = sum_i w_ij f_i + f_ext,j,  w_ij = +1 if j = n_i1, -1 if j = n_i2
//   velocity neuron      v <- v + t_c * (w_v * net + g),  w_v = 1/m  (self-connected)
//   position neuron      p <- p + t_c * v                (weight 1, self-connected)
// The incidence weights +-1 and the position weight 1 are structural: changing
// them would break Newton's third law or dp/dt = v, so they are not stored as
// parameters. 1/m is learnable, per node.
#include <cstdint>
#include <vector>

#include "core/network/cloth_state.h"

namespace neurocloth {

struct MassLayer {
  std::vector<double> inverse_mass;  // velocity-neuron weight 1/m, 1/kg
  std::vector<double> friction;      // Coulomb coefficient used by colliders
  // 1 for a free node, 0 for a pinned one. A multiplier rather than a branch so
  // the node update stays one vectorised loop.
  std::vector<double> free;

  std::size_t size() const { return inverse_mass.size(); }
  bool pinned(std::size_t i) const { return free[i] == 0.0; }
  double mass(std::size_t i) const { return 1.0 / inverse_mass[i]; }
};

}  // namespace neurocloth
