#pragma once
// How large a step the explicit integrators can take. For every free node a
// Gershgorin bound on M^-1 K and M^-1 D gives
//   omega_i^2 = 2 w_i sum_s k_s max_slope,   gamma_i = 2 w_i sum_s d_s
// over the springs s at node i. Semi-implicit Euler on x'' = -omega^2 x - gamma x'
// is stable when h^2 omega^2 + 2 h gamma < 4; with a general limit L on h*omega:
//   h_i = L^2 / (gamma_i + sqrt(gamma_i^2 + L^2 omega_i^2))
// The bound is the minimum over nodes (infinity when nothing constrains it).
// docs/stability.md compares it with the critical steps measured on grids.
#include <string>
#include <vector>

#include "core/integrators/integrator.h"
#include "core/integrators/spectral_bound.h"
#include "core/network/cloth_network.h"

namespace neurocloth {

double stable_step_bound(const ClothNetwork& net, double stability_limit);
// The same with caller-owned scratch (resized to the node count), so a live
// simulation that recomputes the bound after every weight change allocates nothing.
// `with_damping` false: the springs' stiffness alone (gamma 0), for a step that
// takes their damping implicitly (Integrator::damps_springs, spring_damping.h).
double stable_step_bound(const ClothNetwork& net, double stability_limit,
                         std::vector<double>& k_sum, std::vector<double>& d_sum,
                         bool with_damping = true);

// Forward Euler is the exception: on an undamped oscillator it gains energy at
// every step (|1 + i h omega| > 1), so no L makes it stable. With viscosity it
// is stable while h < gamma / omega^2 for every mode, which for damping along
// the springs is h < d_s / (k_s max_slope) (exact when every spring has the
// same ratio), and h < 2 / gamma_i for the overdamped ones. This returns that
// step: 0 when some stiff spring has no damping. Measured in docs/stability.md.
double explicit_euler_step_bound(const ClothNetwork& net);
double explicit_euler_step_bound(const ClothNetwork& net, std::vector<double>& d_sum);

// Which bound sizes the explicit steps: the spectrum's (spectral_bound.h, the
// default: 1.3-1.8 times Gershgorin's step on the shipped cloths) or
// Gershgorin's discs (per node, cheap; what a ramp uses while its weights move
// every step, where a Lanczos run per step would cost more than the steps).
enum class StepBound { spectral, gershgorin };
inline const char* to_string(StepBound b) {
  return b == StepBound::gershgorin ? "gershgorin" : "spectral";
}
inline constexpr const char* kStepBoundNames = "spectral, gershgorin";
inline bool parse_step_bound(const std::string& name, StepBound& out) {
  if (name == "spectral")
    out = StepBound::spectral;
  else if (name == "gershgorin")
    out = StepBound::gershgorin;
  else
    return false;
  return true;
}

// Scratch of the bounds, owned by the caller so a live recompute allocates nothing.
struct StepBoundScratch {
  std::vector<double> k_sum, d_sum;
  SpectralScratch spectral;
};

// The step the adaptive cap and the run-time guard scale by `safety`, in one
// place for every caller: the chosen bound at the integrator's limit (the
// springs' stiffness alone when the integrator damps them itself), and for
// forward Euler also its damped bound above. Where forward Euler has none (a
// spring without damping: no step is stable for ever) the other bound is kept,
// so the step stays finite, and LiveScene::stability_notice() says a
// divergence is coming.
double integrator_step_bound(const ClothNetwork& net, const Integrator& integrator,
                             StepBoundScratch& scratch, StepBound kind = StepBound::spectral);
double integrator_step_bound(const ClothNetwork& net, const Integrator& integrator,
                             StepBound kind = StepBound::spectral);

}  // namespace neurocloth
