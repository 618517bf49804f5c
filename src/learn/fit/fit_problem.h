#pragma once
// The learning stage's objective (paper eq. 18-19): the squared distance between
// the network's node positions and a reference motion, summed over the frames
// and the observed nodes, as a function of the network's weights, with its
// exact gradient by back-propagation through time (rollout.h; each step's
// adjoint beside its step: network_propagation.h, projective.h).
//
// The unknowns form one vector theta in blocks: a family value (the spring
// constant, one number) or, per element, one weight per spring or node (the
// paper's weights). Positive quantities are held as their logarithm, so a
// descent step can never make a mass or a stiffness negative and a factor of 3
// off is the same distance either way.
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/fuzzy/linguistic_variable.h"
#include "core/scene/scene.h"
#include "learn/fit/chamfer.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {

struct FitSettings {
  // Parameter names (docs/learning.md): spring_constant, shear_constant,
  // bend_constant, viscosity, node_mass, rest_length, friction, and module
  // parameters (air_drag.rate, wind.velocity.x, wind.drag, plane.friction, ...),
  // for a material in words its rule base's inputs (input.mass, ...), and
  // control: a pin_motion's keyframes (pin_motion.keyframes) and the cloth's
  // initial_velocity.
  std::vector<std::string> params = {"spring_constant", "viscosity"};
  // One unknown per spring (stiffness, damping, rest length) or node (mass)
  // instead of one per family. Module parameters stay one number each.
  bool per_element = false;
  // Strength of the smoothness regulariser on per-element weights:
  // smoothness * 1/2 sum over neighbouring elements of (log w_i - log w_j)^2.
  double smoothness = 0;
  // The tape's memory budget: above it the forward pass keeps only every K-th
  // state and the backward pass recomputes each segment (rollout.h).
  std::size_t tape_budget_bytes = std::size_t(512) << 20;
  // How a point cloud's frames are compared with the cloth (chamfer.h).
  ChamferSettings chamfer;
  // Strength of the smoothness term on a fitted path (pin_motion.keyframes):
  // path_smoothness * 1/2 sum over inner keys of |o_k-1 - 2 o_k + o_k+1|^2 (m^2).
  double path_smoothness = 0;
};

// One block of theta.
struct FitBlock {
  std::string name;        // "spring_constant", "wind.velocity.x", ...
  std::size_t offset = 0;  // into theta
  std::size_t count = 1;   // 1, or one per spring / node with per_element
  bool log_space = true;   // theta holds log(value)
  std::string unit;        // "N/m", "kg", ...
};

class FitProblem {
 public:
  // Throws InputError (field "--params" or the reference's file) with one line
  // when the scene or the parameters cannot be fitted: an integrator or a module
  // without an adjoint, a parameter the scene does not have, a reference frame
  // after... (see docs/learning.md).
  FitProblem(const Scene& scene, const ReferenceMotion& reference, const FitSettings& settings);
  ~FitProblem();
  FitProblem(FitProblem&&) noexcept;

  std::size_t size() const;  // number of unknowns
  const std::vector<FitBlock>& blocks() const;
  // The scene's own values, in theta's coordinates: where a fit starts.
  Eigen::VectorXd initial() const;
  // theta with every value brought inside the scene's limits (physical_limits.h:
  // a stiffness at most 1e9 N/m, a wind at most 1000 m/s, ...). Every function
  // here reads theta through it: beyond a limit the loss is flat (its gradient
  // there is zero), so a fit can reach a limit but never write a value past it.
  Eigen::VectorXd inside_limits(const Eigen::VectorXd& theta) const;
  // How far a global first stage searches each unknown either way from the
  // start (global_search.h): a decade for a log-space value, a rule base
  // input's whole range, |start| plus a reach for a plain number: 0.25 m for
  // a path's offset, 2 m/s for an initial velocity, 5 m/s for a wind, 0.1
  // otherwise.
  Eigen::VectorXd search_width() const;
  // The values theta stands for (exp of the log-space blocks), inside the limits.
  Eigen::VectorXd values(const Eigen::VectorXd& theta) const;

  // E(theta) = sum_frames sum_observed 1/2 |p_k(t) - y_k(t)|^2 (m^2), or a
  // cloud's Chamfer distance (chamfer.h), plus the regulariser; fills `gradient` (dE/dtheta, exact)
  // when not null. NaN when the forward run produced a non-finite state (then the gradient is NaN
  // too).
  double loss(const Eigen::VectorXd& theta, Eigen::VectorXd* gradient);
  // Root-mean-square distance (m) at theta, from the data term alone.
  double rms_error(const Eigen::VectorXd& theta);
  std::size_t observations() const;  // observed positions or points (3-vectors)
  bool fits_cloud() const;           // the reference is a point cloud (Chamfer loss)
  double duration() const;           // simulated seconds (the last frame's time)
  // Largest tape (checkpoints and one segment) the last loss() held, bytes.
  std::size_t peak_tape_bytes() const;

  // Online adaptation (truncated back-propagation through time): the data term
  // over the `count` steps from step `first`, run from `state` (the running
  // cloth's, not the scene's start) at theta, with its gradient when asked.
  // `end` receives the state after those steps. The regulariser is not in it.
  double window_loss(const Eigen::VectorXd& theta, const ClothState& state, std::size_t first,
                     std::size_t count, Eigen::VectorXd* gradient, ClothState* end);
  // Observed positions in steps [first, first + count).
  std::size_t window_observations(std::size_t first, std::size_t count) const;
  std::size_t step_count() const;         // steps of the whole plan
  double step_time(std::size_t k) const;  // when step k starts
  // The scene's initial state (where the whole plan starts).
  ClothState initial_state() const;
  // The reference's own state at time t, when it observes every node in the
  // two frames around t: positions interpolated between them, velocities their
  // difference over the interval (an estimate: a recording keeps no
  // velocities). False, `state` untouched, when it does not (markers).
  bool reference_state(double t, ClothState& state) const;

  // The scene with theta's family values written into its material and
  // modules (the material becomes numeric). Per-element blocks are not in it:
  // see element_weights.
  Scene fitted_scene(const Eigen::VectorXd& theta) const;
  // A fit of a material's inputs (input.NAME): each fitted input at theta in
  // the rule base's words, "elasticity 0.712: big 0.80, medium 0.20"; empty
  // for other fits.
  std::vector<std::string> inputs_in_words(const Eigen::VectorXd& theta) const;
  // The rule base's variable a block of theta fits (input.NAME), or null.
  const fuzzy::LinguisticVariable* input_variable(const FitBlock& block) const;
  // Every weight of the network the fit runs at theta (network order): the
  // side file holds them when fitted_scene's material alone does not build them.
  MaterialWeights element_weights(const Eigen::VectorXd& theta) const;
  std::vector<double> element_rest_lengths(const Eigen::VectorXd& theta) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace neurocloth
