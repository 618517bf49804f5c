#pragma once
// Back-propagation through time (paper eq. 18-19) for the network integrator:
// a forward run that keeps what the backward run needs (a tape), and the
// backward run that carries dE/d(state) from the last step to the first,
// collecting dE/d(weight) on its way. Hand-written: each step's adjoint undoes
// the step's lines in reverse (docs/learning.md, "The gradient").
//
// Memory: the tape holds every state (and, when the scene has constraints, the
// state before each constraint) while that fits the budget; above it only every
// K-th state is kept and the backward run recomputes each segment of K steps
// from its checkpoint (one more forward pass, memory ~ (T/K + K) states).
#include <array>
#include <memory>
#include <vector>

#include "core/integrators/integrator.h"
#include "core/network/cloth_network.h"
#include "core/network/spring_adjoint.h"
#include "core/network/spring_kernel.h"
#include "learn/fit/frame_loss.h"
#include "learn/fit/observation_plan.h"
#include "learn/fit/step_plan.h"

namespace neurocloth {

// The model a rollout reads: a network with its force modules, and the
// constraints run after each step, in run order (what Scene::make_simulation
// builds).
struct RolloutModel {
  ClothNetwork net;
  std::vector<std::shared_ptr<const ConstraintModule>> constraints;
  // The step the run takes: the paper's network propagation, or `projective`
  // with its iterations (projective.h: a fixed count, read backwards exactly).
  IntegratorKind integrator = IntegratorKind::network;
  int iterations = kDefaultProjectiveIterations;
  // The code that evaluates the springs' forces and their adjoint
  // (SolverSettings::kernel): the scene's own, so that a fit runs the steps
  // its plan was measured on, to the same last bits.
  SpringKernel kernel = SpringKernel::automatic;
};

// dE/d(weight) in the network's order, and dE/d(module parameter) per module
// slot (parameter_id.h: module_slot; a constraint's path after its slots:
// ConstraintModule::gradient_slots).
struct RolloutGradients {
  SpringGradients springs;
  std::vector<double> inverse_mass, friction;  // per node
  std::vector<std::array<double, kModuleParameterSlots>> force_modules;
  std::vector<std::vector<double>> constraints;
  // dE/d(the initial state), when `want_initial` (a fitted initial velocity).
  bool want_initial = false;
  ClothState initial;
};

class Rollout {
 public:
  // `steps` starts at the initial state's time (0). Every frame lies in [0, steps.end()].
  Rollout(ClothState initial, StepPlan steps, ObservationPlan observations,
          std::size_t tape_budget_bytes);
  ~Rollout();

  // Runs the model forward over the plan and returns the data term
  // E = sum 1/2 |p(t) - y|^2 (m^2); NaN when the run left finite numbers.
  // With `gradients`, runs backward too and sets them (sized for the model).
  double run(const RolloutModel& model, RolloutGradients* gradients);

  // The state the next run starts from (a fitted initial velocity changes it).
  void set_initial(const ClothState& initial);
  const ClothState& initial() const { return initial_; }
  // The state after the last step of the last run.
  const ClothState& final_state() const { return final_; }
  // The positions compared with each node observation at the last run (m).
  const std::vector<Vec3>& compared() const { return compared_; }
  // Observed 3-vectors (node observations and clouds' points).
  std::size_t data_count() const { return obs_.data_count(); }
  // Largest memory the tape held in a run so far (checkpoints + a segment), bytes.
  std::size_t peak_tape_bytes() const { return peak_bytes_; }
  // Steps per recomputed segment (the step count when everything fits).
  std::size_t segment_steps() const { return segment_; }
  const StepPlan& steps() const { return steps_; }

 private:
  struct Tape;
  void step_forward(const RolloutModel& m, std::size_t k, const ClothState& in, ClothState& out,
                    ClothState* pre_constraints);
  void observe(std::size_t k, const ClothState& before, const ClothState& after);
  void add_loss_gradient(std::size_t state_index, ClothState& adj) const;
  void step_backward(const RolloutModel& m, std::size_t k, const ClothState& in,
                     const ClothState* pre_constraints, ClothState& adj, RolloutGradients& g);
  void prepare_integrator(const RolloutModel& m);

  ClothState initial_;
  StepPlan steps_;
  ObservationPlan obs_;
  std::size_t budget_;
  std::size_t segment_ = 0;
  std::size_t peak_bytes_ = 0;
  std::vector<Vec3> compared_;
  // Per cloud: its loss and dE/dp at the last run, and every node's position
  // at a cloud's time (scratch).
  std::vector<double> cloud_loss_;
  std::vector<std::vector<Vec3>> cloud_gradient_;
  std::vector<Vec3> at_frame_;
  ClothState final_;
  // For each step, the frames that compare states k and k+1.
  std::vector<std::size_t> frames_of_step_begin_;
  std::unique_ptr<Tape> tape_;
};

}  // namespace neurocloth
