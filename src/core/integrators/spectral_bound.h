#pragma once
// The explicit step bound with the damping's part from the spectrum itself
// rather than Gershgorin's discs.
//
// A spring's damping d u u^T is at most d I (u u^T <= I), so M^-1 D is bounded
// by the scalar graph Laplacian L_d of the springs' viscosities over the free
// nodes' masses: lambda_D <= lambda_max(M^-1 L_d), whatever the cloth's shape.
// Gershgorin bounds it by 2 w_i sum_s d_s at the worst node; the true top
// eigenvalue of a cloth's grid is well below it (16.3 against 24 inside for
// equal damping on structural, shear and bend springs, and further still at the
// light edge and corner nodes). Semi-implicit Euler with damping is stable
// while h^2 omega^2 + 2 h gamma < 4 (stability.h), so on a fine cloth, where
// the damping sets the step, the step grows by as much.
//
// The springs' part (omega^2) stays Gershgorin's largest disc. The same
// Laplacian bound holds for it only while every spring's Jacobian is at most
// k |slope| I, which a compressed spring's negative transverse stiffness
// breaks (below half its rest length), and it was measured to fail: on the
// 128^2 drape with the damping taken implicitly, a cap at 0.5 of the spectral
// stiffness bound diverged in contact at 0.90 s where Gershgorin's ran
// (docs/stability.md).
//
// The top eigenvalue comes from Lanczos with a fixed pseudo-random start. Its
// Ritz value approaches from below, so it is divided by (1 - delta): by
// Kuczynski and Wozniakowski (1992), for a positive semi-definite n x n matrix
// P(relative error >= delta) <= 1.648 sqrt(n) exp(-sqrt(delta) (2k - 1)), and
// k is chosen for delta = 0.02 at a probability of 1e-12. The Gershgorin bound
// stays the floor: the result is never below stable_step_bound().
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

// The estimate rounded up to kSpectralBits significant bits (a step a little
// smaller, never larger). The unrounded estimate's last bits differ between
// builds (measured: -O3 against the sanitizers' -O1 on the same AVX-512 CPU,
// the 0.3 s hanging_fuzzy run to other bits; which sum differs is untraced); a
// step rounded this coarsely keeps the run's bits a function of the cloth
// (determinism_test), unless an estimate straddles a rounding edge (about 1 in
// 2^(52 - kSpectralBits) per estimate).
constexpr int kSpectralBits = 24;
double spectral_round_up(double x);

// How many Lanczos steps the bound takes for n free nodes (at most n).
int spectral_lanczos_steps(std::size_t n);

// An upper bound (in the sense above) on the largest eigenvalue of
// M^-1/2 L_c M^-1/2 over the free nodes, L_c the scalar Laplacian with spring
// weights `weight` (>= 0, one per spring). 0 when no free node has a spring.
double laplacian_top_eigenvalue(const ClothNetwork& net, const std::vector<double>& weight,
                                SpectralScratch& scratch);

// The step bound at the integrator's limit: the damping's part from the
// spectrum, the springs' from Gershgorin's largest disc, or Gershgorin's
// per-node bound where that is larger. `with_damping` false (the damping taken
// implicitly, spring_damping.h): Gershgorin's bound itself. Infinity when
// nothing constrains it.
double spectral_step_bound(const ClothNetwork& net, double stability_limit,
                           SpectralScratch& scratch, bool with_damping = true);

}  // namespace neurocloth
