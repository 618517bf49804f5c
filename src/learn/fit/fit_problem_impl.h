#pragma once
// FitProblem's inside, shared by the files that hold it: fit_problem.cpp (the
// model, construction, theta's coordinates), fit_parameters.cpp (the --params
// names to blocks of theta), fit_mapping.cpp (theta to the model and the
// gradient back), observation_plan.cpp (the reference's frames to the plan),
// fit_loss.cpp (the loss at theta) and fitted_scene.cpp (theta written back
// into a scene).
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/network/parameter_id.h"
#include "core/scene/fuzzy_material.h"
#include "learn/fit/fit_problem.h"
#include "learn/fit/rollout.h"

namespace neurocloth {
namespace fit_detail {

// What a block of theta sets in the model.
enum class Target {
  stiffness,         // spring_constant / shear_constant / bend_constant: b1 of `elements`
  viscosity,         // b2 of `elements` (every spring)
  node_mass,         // 1 / w of `elements` (every node), times the node's mass share
  rest_length,       // L of `elements`: a scale on the scene's lengths, or each length
  friction,          // the material's Coulomb coefficient, every node
  force_module,      // a parameter of net.force_modules[module]
  constraint,        // a parameter of constraints[module]
  input,             // a linguistic input of the scene's rule base: the whole material
  path,              // the keyframe offsets of constraints[module] (a pin_motion), x y z each
  initial_velocity,  // every unpinned node's velocity at t = 0, x y z
};

struct Unknown {
  FitBlock block;
  Target target;
  bool per_element = false;
  std::vector<std::int32_t> elements;  // springs or nodes it sets
  int module = -1;                     // index into the model's force modules or constraints
  int declaration = -1;                // the module's index in the scene's declarations
  ParameterId id;                      // module parameter (parameter and axis)
  int input = -1;                      // the rule base's input (Target::input)
  double base = 1;                     // family value at the start (rest length: 1, a scale)
  // The scene's limits on the value (physical_limits.h): a fitted value stays
  // inside them, so FITTED.json loads (Impl::inside).
  double low = -HUGE_VAL, high = HUGE_VAL;
  // Per-element blocks: pairs of neighbouring elements the smoothness term ties.
  std::vector<std::pair<std::int32_t, std::int32_t>> neighbours;
  // Blocks of plain numbers (a path, a velocity): where each starts.
  std::vector<double> starts;
  // A path: the keyframes it fits (a first key at t <= 0 stays where the scene
  // put it: the pins start there).
  std::vector<std::size_t> keys;
};

[[noreturn]] void refuse(const std::string& message);
// Writes a module parameter into a module's declaration.
void set_spec_parameter(ModuleSpec& spec, const ParameterId& id, double value);
// Writes a path's fitted keyframe offsets (theta's block of `u`) into its
// pin_motion's declaration.
void set_path(ModuleSpec& spec, const Unknown& u, const Eigen::VectorXd& theta);

}  // namespace fit_detail

struct FitProblem::Impl {
  Scene scene;
  FitSettings settings;
  RolloutModel base;   // the scene's model
  RolloutModel model;  // the model at the last theta
  std::vector<fit_detail::Unknown> unknowns;
  std::vector<FitBlock> blocks;
  std::size_t size = 0;
  std::unique_ptr<Rollout> rollout;
  StepPlan steps;                   // the whole run's
  ObservationPlan observed;         // the whole run's
  std::vector<double> frame_times;  // the reference's, one per observed frame
  RolloutGradients gradients;
  double duration = 0;
  // A fit of linguistic inputs: the material at the last theta and, per input
  // unknown, its derivatives (FuzzyMaterial::sensitivity).
  bool words = false;
  Material material;
  std::vector<Material> d_material;

  void build_model();
  void parse_parameters();
  void add_family(const std::string& name, fit_detail::Target target,
                  std::vector<std::int32_t> elements, double value, const std::string& unit,
                  bool per_element);
  void add_input(const std::string& name);
  void add_path(const std::string& name, int declaration);
  int constraint_of(int declaration) const;
  void add_initial_velocity();
  ClothState start;  // the scene's initial state (a fitted initial velocity changes it)
  void plan(const ReferenceMotion& reference);
  void apply(const Eigen::VectorXd& theta);
  Eigen::VectorXd inside(const Eigen::VectorXd& theta) const;
  void zero_outside(const Eigen::VectorXd& theta, const Eigen::VectorXd& in,
                    Eigen::VectorXd& gradient) const;
  double regulariser(const Eigen::VectorXd& theta, Eigen::VectorXd* gradient) const;
  void chain(const Eigen::VectorXd& theta, Eigen::VectorXd& gradient) const;
  // The rule base's inputs at theta: the scene's, with the fitted ones replaced.
  std::map<std::string, double> inputs_at(const Eigen::VectorXd& theta) const;
  double input_gradient(const Material& d) const;
};

}  // namespace neurocloth
