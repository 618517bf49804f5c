#pragma once
// The spring layer read backwards (learning, docs/learning.md): the adjoint of
// the springs' part of ClothNetwork::net_forces. Given dE/dF at every node, it
// gives dE/dp and dE/dv of the state the forces were evaluated at, and the
// gradients of the layer's weights (b1, b2 and the rest lengths). Exact: it
// differentiates the same expressions, spring by spring, in the same chunks.
#include <vector>

#include "core/network/cloth_network.h"

namespace neurocloth {

// dE/d(weight), one per spring in the network's order; accumulated (+=), so a
// sum over the steps of a run builds up in place.
struct SpringGradients {
  std::vector<double> stiffness, damping, rest_length;
  void resize(std::size_t springs) {
    for (auto* g : {&stiffness, &damping, &rest_length})
      g->assign(springs, 0.0);
  }
};

// Adds the springs' contribution: adj += (dF/d state)^T adj_force, g += (dF/dw)^T adj_force.
// `g` must be sized for the network's springs. `kernel`: the one the forces
// were evaluated by (ForceContext::kernel), whose arithmetic is differentiated;
// throws std::invalid_argument, before any work, when the CPU cannot run it.
void spring_forces_adjoint(const ClothNetwork& net, const ClothState& state,
                           const NodeVectors& adj_force, ClothState& adj, SpringGradients& g,
                           SpringKernel kernel = SpringKernel::automatic);

}  // namespace neurocloth
