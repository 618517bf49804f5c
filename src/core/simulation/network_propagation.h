#pragma once
// The paper's propagation, forwards and backwards. Forwards it is an
// Integrator (network_propagation.cpp, made by make_network_propagation in
// integrators/integrator_factory.h); backwards it is the step's adjoint
// (network_propagation_adjoint.cpp), what a fit's rollout runs for each step
// in reverse, as projective's adjoint sits beside projective.
#include "core/network/cloth_network.h"
#include "core/network/force_context.h"
#include "core/network/force_inputs.h"
#include "core/network/spring_adjoint.h"

namespace neurocloth {

// One network step of `h` from `in` (explicit damping, as a fit runs it)
// taken backwards. Forwards it was
//   v' = v + h free (w F(in) + g),  p' = p + h v'.
// On entry `adj` holds dE/d(p', v'), the constraints' share through the step's
// start already taken out into `adj_start` (dE/dp of the start; null when the
// step has no constraints). On return `adj` holds dE/d(p, v) of `in` from the
// step and the springs, `adj_force` dE/dF for the forces of the scene's other
// modules to carry back (their adjoint is the caller's, as for every
// integrator), `g` and `adj_inverse_mass` (null: not wanted) have the step's
// share added. `forces` is scratch of the network's size.
void network_step_adjoint(const ClothNetwork& net, const ForceInputs& inputs,
                          const ForceContext& context, const ClothState& in, double h,
                          const NodeVectors* adj_start, ClothState& adj, NodeVectors& adj_force,
                          NodeVectors& forces, SpringGradients& g, double* adj_inverse_mass);

}  // namespace neurocloth
