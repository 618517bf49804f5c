// The network step's adjoint (network_propagation.h): the propagation's
// arithmetic read backwards, in the order that makes every gradient exactly
// the derivative of the forward step's expressions.
#include "core/simulation/network_propagation.h"

namespace neurocloth {

void network_step_adjoint(const ClothNetwork& net, const ForceInputs& inputs,
                          const ForceContext& context, const ClothState& in, double h,
                          const NodeVectors* adj_start, ClothState& adj, NodeVectors& adj_force,
                          NodeVectors& forces, SpringGradients& g, double* adj_inverse_mass) {
  // From dE/d(p', v'): lv = dE/dv' + h dE/dp' is dE/dv, dE/dF = h free w lv,
  // dE/dw += h free F.lv, dE/dp = dE/dp' (+ the constraints' share); then
  // the springs' own adjoint through F.
  const std::size_t n = net.node_count();
  const double* w = net.masses.inverse_mass.data();
  const double* free = net.masses.free.data();
  double* const lp[3] = {adj.x.data(), adj.y.data(), adj.z.data()};
  double* const lv[3] = {adj.vx.data(), adj.vy.data(), adj.vz.data()};
  double* const lF[3] = {adj_force.x.data(), adj_force.y.data(), adj_force.z.data()};
  for (int c = 0; c < 3; ++c) {
    double* __restrict p = lp[c];
    double* __restrict v = lv[c];
    double* __restrict f = lF[c];
#pragma GCC ivdep
    for (std::size_t i = 0; i < n; ++i) {
      v[i] += h * p[i];
      f[i] = h * free[i] * w[i] * v[i];
    }
  }
  if (adj_start) {
    const double* const lb[3] = {adj_start->x.data(), adj_start->y.data(), adj_start->z.data()};
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i)
        lp[c][i] += lb[c][i];
  }
  if (adj_inverse_mass) {
    net.net_forces(in, inputs, context, forces);
    for (std::size_t i = 0; i < n; ++i)
      adj_inverse_mass[i] +=
          h * free[i] *
          (forces.x[i] * adj.vx[i] + forces.y[i] * adj.vy[i] + forces.z[i] * adj.vz[i]);
  }
  spring_forces_adjoint(net, in, adj_force, adj, g, context.kernel);
}

}  // namespace neurocloth
