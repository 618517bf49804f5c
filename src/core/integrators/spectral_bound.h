#pragma once
// The explicit step bound from the spectrum itself rather than Gershgorin's discs.
//
// Each spring's stiffness Jacobian is at most k |slope| I and its damping d u u^T
// at most d I (u u^T <= I), so M^-1 K and M^-1 D are bounded by the scalar
// graph Laplacians L_k, L_d of the springs (weights k |slope| and d) over the
// free nodes' masses: lambda_K <= lambda_max(M^-1 L_k), likewise lambda_D.
// Gershgorin bounds those by 2 w_i sum_s c_s at the worst node; the true top
// eigenvalue of a cloth's grid is well below it (interior 16.3 against 24 for
// equal damping on structural, shear and bend springs; at the light edge and
// corner nodes further still). Semi-implicit Euler with damping is stable while
// M - h D / 2 - h^2 K / 4 > 0, which holds when h^2 lambda_K + 2 h lambda_D < 4:
// the same formula as stability.h with gamma -> lambda_D, omega^2 -> lambda_K.
//
// The top eigenvalue comes from Lanczos with a fixed pseudo-random start. Its
// Ritz value approaches from below, so it is divided by (1 - delta): by
// Kuczynski and Wozniakowski (1992), for a positive semi-definite n x n matrix
// P(relative error >= delta) <= 1.648 sqrt(n) exp(-sqrt(delta) (2k - 1)), and
// k is chosen for delta = 0.02 at a probability of 1e-12. The Gershgorin bound
// stays the floor: the result is never below stable_step_bound().
// docs/stability.md ("The spectral bound") gives the measured steps.
#include <vector>

#include "core/network/cloth_network.h"

namespace neurocloth {

// Scratch for the Lanczos vectors: the node-sized ones are reused from one
// recompute to the next (the tridiagonal's eigen solve still allocates its own).
struct SpectralScratch {
  std::vector<double> scale;         // sqrt(1/m) on free nodes, 0 on pinned ones
  std::vector<double> weight;        // |weight| of each spring
  std::vector<double> k_sum, d_sum;  // Gershgorin's, the floor
  std::vector<double> prev, cur, next, spread;
  std::vector<double> alpha, beta;
};

// How many Lanczos steps the bound takes for n free nodes (at most n).
int spectral_lanczos_steps(std::size_t n);

// An upper bound (in the sense above) on the largest eigenvalue of
// M^-1/2 L_c M^-1/2 over the free nodes, L_c the scalar Laplacian with spring
// weights `weight` (>= 0, one per spring). 0 when no free node has a spring.
double laplacian_top_eigenvalue(const ClothNetwork& net, const std::vector<double>& weight,
                                SpectralScratch& scratch);

// The step bound at the integrator's limit: the spectral bound above, or
// Gershgorin's where that is larger. `with_damping` false: stiffness alone (the
// damping taken implicitly, spring_damping.h). Infinity when nothing constrains it.
double spectral_step_bound(const ClothNetwork& net, double stability_limit,
                           SpectralScratch& scratch, bool with_damping = true);

}  // namespace neurocloth
