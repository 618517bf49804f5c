#pragma once
// How large a step the explicit integrators can take. For every free node a
// Gershgorin bound on M^-1 K and M^-1 D gives
//   omega_i^2 = 2 w_i sum_s k_s max_slope,   gamma_i = 2 w_i sum_s d_s
// over the springs s at node i. Semi-implicit Euler on x'' = -omega^2 x - gamma x'
// is stable when h^2 omega^2 + 2 h gamma < 4; with a general limit L on h*omega:
//   h_i = L^2 / (gamma_i + sqrt(gamma_i^2 + L^2 omega_i^2))
// The bound is the minimum over nodes (infinity when nothing constrains it).
#include "cloth_network.h"

namespace neurocloth {

double stable_step_bound(const ClothNetwork& net, double stability_limit);

}  // namespace neurocloth
