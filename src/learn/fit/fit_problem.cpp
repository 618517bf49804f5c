// The FitProblem itself (fit_problem.h): the model a fit runs built from the
// scene, refused when it has no adjoint; construction; and theta's
// coordinates (its start, its limits, its search widths, its values). The
// rest of the class lives in the files named after what they hold:
// fit_loss.cpp, observation_plan.cpp, fitted_scene.cpp, with fit_parameters.cpp
// and fit_mapping.cpp (fit_problem_impl.h).
#include "learn/fit/fit_problem.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/io/input_error.h"
#include "core/modules/module_set.h"
#include "learn/fit/fit_problem_impl.h"

namespace neurocloth {
using namespace fit_detail;

void FitProblem::Impl::build_model() {
  const SolverSettings& s = scene.solver;
  if (s.integrator != IntegratorKind::network && s.integrator != IntegratorKind::projective)
    throw InputError(scene.path, "solver.integrator",
                     std::string("fit: integrator '") + to_string(s.integrator) +
                         "' has no adjoint (fit runs the network integrator, fixed or adaptive, "
                         "and projective)");
  // The adjoint differentiates the double step: a float forward pass would
  // make its gradients those of another function.
  if (s.precision != SpringPrecision::float64)
    throw InputError(scene.path, "solver.precision",
                     std::string("fit: precision '") + to_string(s.precision) +
                         "' has no adjoint (learning differentiates the double step); set it "
                         "to \"double\" to fit this scene");
  if (s.damping != DampingMode::explicit_force)
    throw InputError(scene.path, "solver.damping",
                     std::string("fit: damping '") + to_string(s.damping) +
                         "' has no adjoint (learning differentiates the paper's step, damping in "
                         "the force sum); set it to \"explicit\" to fit this scene");
  base.net = scene.build_network();
  base.integrator = s.integrator;
  base.iterations = s.iterations;
  base.kernel = s.kernel;
  // The scene's modules in the order Scene::make_simulation runs them, and
  // which declaration each one came from.
  std::vector<std::pair<int, std::shared_ptr<const ConstraintModule>>> constraints;
  for (std::size_t d = 0; d < scene.modules.size(); ++d) {
    ModuleSet one = build_modules({scene.modules[d]}, scene.topology);
    for (auto& f : one.forces) {
      if (!f->has_adjoint())
        throw InputError(scene.path, "modules[" + std::to_string(d) + "]",
                         std::string("fit: module '") + f->type() + "' has no adjoint");
      base.net.force_modules.push_back(std::move(f));
    }
    for (auto& c : one.constraints) {
      if (!c->has_adjoint() || c->make_state())
        throw InputError(scene.path, "modules[" + std::to_string(d) + "]",
                         std::string("fit: module '") + c->type() + "' has no adjoint");
      constraints.emplace_back(static_cast<int>(d), std::move(c));
    }
  }
  std::stable_sort(constraints.begin(), constraints.end(), [](const auto& a, const auto& b) {
    return a.second->phase() < b.second->phase();
  });
  for (auto& c : constraints)
    base.constraints.push_back(c.second);
  model = base;
}

FitProblem::FitProblem(const Scene& scene, const ReferenceMotion& reference,
                       const FitSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.scene = scene;
  m.settings = settings;
  if (!(settings.smoothness >= 0) || !std::isfinite(settings.smoothness))
    throw InputError("command line", "--smoothness", "must be a finite number >= 0");
  if (!(settings.path_smoothness >= 0) || !std::isfinite(settings.path_smoothness))
    throw InputError("command line", "--path-smoothness", "must be a finite number >= 0");
  m.build_model();
  m.start = scene.initial_state();
  m.plan(reference);
  m.parse_parameters();
  // A per-element weight of 0 (a side file may hold one: a spring without
  // stiffness, damping or length) has no logarithm to start from.
  const Eigen::VectorXd start = initial();
  for (const Unknown& u : m.unknowns)
    for (std::size_t e = 0; e < u.block.count; ++e)
      if (!std::isfinite(start[static_cast<Eigen::Index>(u.block.offset + e)]))
        refuse("'" + u.block.name + "' of " +
               (u.target == Target::node_mass ? "node " : "spring ") +
               std::to_string(u.elements[e]) +
               " is 0 in the scene: a fit in log space needs every start > 0 (leave it out, or "
               "fit it per family)");
  bool masses = false, friction = false;
  for (const Unknown& u : m.unknowns) {
    masses |= u.target == Target::node_mass || u.target == Target::input;
    friction |= u.target == Target::friction || u.target == Target::input;
  }
  // Only what a fit asks for is collected (the inverse mass needs the forces again).
  if (masses) m.gradients.inverse_mass.assign(m.base.net.node_count(), 0.0);
  if (friction) m.gradients.friction.assign(m.base.net.node_count(), 0.0);
}

FitProblem::~FitProblem() = default;
FitProblem::FitProblem(FitProblem&&) noexcept = default;

std::size_t FitProblem::size() const {
  return impl_->size;
}
const std::vector<FitBlock>& FitProblem::blocks() const {
  return impl_->blocks;
}

Eigen::VectorXd FitProblem::initial() const {
  Eigen::VectorXd theta(static_cast<Eigen::Index>(impl_->size));
  const ClothNetwork& net = impl_->base.net;
  for (const Unknown& u : impl_->unknowns) {
    for (std::size_t e = 0; e < u.block.count; ++e) {
      if (!u.starts.empty()) {  // plain numbers: a path, a velocity
        theta[static_cast<Eigen::Index>(u.block.offset + e)] = u.starts[e];
        continue;
      }
      double v = u.base;
      if (u.per_element) {
        const auto k = static_cast<std::size_t>(u.elements[e]);
        if (u.target == Target::stiffness) v = net.springs.stiffness[k];
        if (u.target == Target::viscosity) v = net.springs.damping[k];
        if (u.target == Target::node_mass) v = net.mass(k);
        if (u.target == Target::rest_length) v = net.springs.rest_length[k];
      }
      theta[static_cast<Eigen::Index>(u.block.offset + e)] = u.block.log_space ? std::log(v) : v;
    }
  }
  return theta;
}

Eigen::VectorXd FitProblem::search_width() const {
  const Eigen::VectorXd start = initial();
  Eigen::VectorXd w(static_cast<Eigen::Index>(impl_->size));
  for (const Unknown& u : impl_->unknowns)
    for (std::size_t e = 0; e < u.block.count; ++e) {
      const auto i = static_cast<Eigen::Index>(u.block.offset + e);
      // Plain numbers: how far a user's guess may be off, by what they are
      // (a throw by hand is a few m/s, a corner's path some decimetres).
      const double reach = u.target == Target::path               ? 0.25
                           : u.target == Target::initial_velocity ? 2.0
                           : u.target == Target::force_module     ? 5.0  // a wind, m/s
                                                                  : 0.1;
      w[i] = u.block.log_space           ? std::log(10.0)
             : u.target == Target::input ? u.high - u.low
                                         : std::abs(start[i]) + reach;
    }
  return w;
}

Eigen::VectorXd FitProblem::inside_limits(const Eigen::VectorXd& theta) const {
  return impl_->inside(theta);
}

Eigen::VectorXd FitProblem::values(const Eigen::VectorXd& theta_in) const {
  const Eigen::VectorXd theta = impl_->inside(theta_in);
  Eigen::VectorXd v = theta;
  for (const FitBlock& b : impl_->blocks)
    if (b.log_space)
      for (std::size_t e = 0; e < b.count; ++e)
        v[static_cast<Eigen::Index>(b.offset + e)] =
            std::exp(theta[static_cast<Eigen::Index>(b.offset + e)]);
  return v;
}

}  // namespace neurocloth
