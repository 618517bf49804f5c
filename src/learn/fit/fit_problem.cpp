#include "learn/fit/fit_problem.h"

#include <algorithm>
#include <cmath>

#include "core/fuzzy/term_degrees.h"
#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "core/modules/module_set.h"
#include "core/network/parameter_id.h"
#include "learn/fit/fit_problem_impl.h"
#include "learn/fit/rollout.h"

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

void FitProblem::Impl::plan(const ReferenceMotion& ref) {
  if (ref.frames.empty()) throw InputError(ref.path, "frames", "the reference has no frames");
  const std::size_t n = base.net.node_count();
  duration = ref.frames.back().time;
  if (!(duration > 0))
    throw InputError(ref.path, "time", "the reference ends at t = 0: nothing to fit to");
  // A fit runs the scene to the last frame many times: a reference whose time
  // runs to years would never finish (or allocate a plan of that many steps).
  if (!(duration / scene.solver.dt <= static_cast<double>(kMaxFitSteps)))
    throw InputError(ref.path, "time",
                     "the reference ends at t = " + show_number(duration) +
                         " s: " + show_number(duration / scene.solver.dt) +
                         " steps of the scene's dt; a fit runs at most 1e7");
  // A projective run keeps every iteration's Chebyshev weight for its adjoint
  // (16 bytes each), and each iteration is a solve: a plan of more iterations
  // than this is refused before it allocates them.
  if (base.integrator == IntegratorKind::projective &&
      duration / scene.solver.dt * scene.solver.iterations > kMaxFitIterations)
    throw InputError(scene.path, "solver.iterations",
                     "fit: " + show_number(duration / scene.solver.dt) + " steps of " +
                         std::to_string(scene.solver.iterations) +
                         " projective iterations to reach t = " + show_number(duration) +
                         " s; a fit runs at most 1e7 iterations: fewer iterations, larger "
                         "steps or a shorter reference");
  StepPlan steps;
  try {
    steps = plan_steps(scene, duration);
  } catch (const std::runtime_error& e) {
    throw InputError(scene.path, "solver", std::string("fit: ") + e.what());
  }
  ObservationPlan obs;
  std::shared_ptr<const ClothSurface> surface;
  if (ref.is_cloud()) {
    if (scene.topology.triangles.empty())
      throw InputError(ref.path, "points",
                       "a point cloud is compared with the cloth's triangles, and this scene's "
                       "cloth has none (a chain)");
    surface = std::make_shared<const ClothSurface>(scene.topology.triangles, n);
  }
  for (const ReferenceFrame& f : ref.frames) {
    if (!(f.time >= 0))
      throw InputError(ref.path, "time", "a frame before the scene's start (t < 0)");
    ObservationPlan::Frame fr;
    const auto it = std::upper_bound(steps.start.begin(), steps.start.end(), f.time);
    fr.step =
        it == steps.start.begin() ? 0 : static_cast<std::size_t>(it - steps.start.begin()) - 1;
    fr.step = std::min(fr.step, steps.count() - 1);
    fr.alpha = std::clamp((f.time - steps.start[fr.step]) / steps.size[fr.step], 0.0, 1.0);
    if (ref.is_cloud()) {
      if (f.positions.empty())
        throw InputError(ref.path, "points",
                         "the frame at t = " + show_number(f.time) + " s has no points");
      fr.cloud = static_cast<int>(obs.clouds.size());
      fr.count = f.positions.size();
      obs.clouds.push_back(
          std::make_shared<const ChamferTarget>(f.positions, surface, settings.chamfer));
      obs.frames.push_back(fr);
      frame_times.push_back(f.time);
      continue;
    }
    fr.first = obs.nodes.size();
    fr.count = f.nodes.size();
    for (std::size_t k = 0; k < f.nodes.size(); ++k) {
      const std::int32_t file_node = f.nodes[k];
      if (file_node < 0 || static_cast<std::size_t>(file_node) >= n)
        throw InputError(ref.path, "node",
                         "node " + std::to_string(file_node) + " is not in the scene (it has " +
                             std::to_string(n) + " nodes)");
      obs.nodes.push_back(scene.topology.numbering.node(file_node));
      obs.targets.push_back(f.positions[k]);
    }
    obs.frames.push_back(fr);
    frame_times.push_back(f.time);
  }
  this->steps = steps;
  observed = obs;
  rollout = std::make_unique<Rollout>(scene.initial_state(), std::move(steps), std::move(obs),
                                      settings.tape_budget_bytes);
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

double FitProblem::loss(const Eigen::VectorXd& theta, Eigen::VectorXd* gradient) {
  Impl& m = *impl_;
  if (static_cast<std::size_t>(theta.size()) != m.size)
    throw std::invalid_argument("FitProblem::loss: theta has the wrong size");
  if (!theta.allFinite()) {
    if (gradient) gradient->setConstant(static_cast<Eigen::Index>(m.size), std::nan(""));
    return std::nan("");
  }
  const Eigen::VectorXd in = m.inside(theta);
  m.apply(in);
  const double data = m.rollout->run(m.model, gradient ? &m.gradients : nullptr);
  if (!gradient) return data + m.regulariser(in, nullptr);
  if (!std::isfinite(data)) {
    gradient->setConstant(static_cast<Eigen::Index>(m.size), std::nan(""));
    return data;
  }
  m.chain(in, *gradient);
  const double r = m.regulariser(in, gradient);
  m.zero_outside(theta, in, *gradient);
  return data + r;
}

double FitProblem::window_loss(const Eigen::VectorXd& theta, const ClothState& state,
                               std::size_t first, std::size_t count, Eigen::VectorXd* gradient,
                               ClothState* end) {
  Impl& m = *impl_;
  if (first >= m.steps.count() || count == 0)
    throw std::invalid_argument("FitProblem::window_loss: no such steps");
  count = std::min(count, m.steps.count() - first);
  const Eigen::VectorXd in = m.inside(theta);
  m.apply(in);
  Rollout window(state, window_of(m.steps, first, count), window_of(m.observed, first, count),
                 m.settings.tape_budget_bytes);
  const double data = window.run(m.model, gradient ? &m.gradients : nullptr);
  if (end) *end = window.final_state();
  if (gradient) {
    if (std::isfinite(data)) {
      m.chain(in, *gradient);
      m.zero_outside(theta, in, *gradient);
    } else
      gradient->setConstant(static_cast<Eigen::Index>(m.size), std::nan(""));
  }
  return data;
}

std::size_t FitProblem::window_observations(std::size_t first, std::size_t count) const {
  std::size_t n = 0;
  for (const ObservationPlan::Frame& f : impl_->observed.frames)
    if (f.step >= first && f.step < first + count) n += f.count;
  return n;
}

std::size_t FitProblem::step_count() const {
  return impl_->steps.count();
}
double FitProblem::step_time(std::size_t k) const {
  return impl_->steps.start.at(k);
}
ClothState FitProblem::initial_state() const {
  return impl_->scene.initial_state();
}

bool FitProblem::reference_state(double t, ClothState& state) const {
  const Impl& m = *impl_;
  const std::vector<double>& ft = m.frame_times;
  const std::size_t n = m.base.net.node_count();
  if (ft.size() < 2 || !(t >= ft.front()) || !(t <= ft.back())) return false;
  // Frame f observes every node, in the order frame 0 lists them.
  const auto full = [&](std::size_t f) {
    const ObservationPlan::Frame& fr = m.observed.frames[f];
    if (fr.cloud >= 0 || fr.count != n) return false;  // a cloud names no node
    const ObservationPlan::Frame& first = m.observed.frames[0];
    return first.count == n && std::equal(m.observed.nodes.begin() + std::ptrdiff_t(fr.first),
                                          m.observed.nodes.begin() + std::ptrdiff_t(fr.first + n),
                                          m.observed.nodes.begin() + std::ptrdiff_t(first.first));
  };
  const auto at = [&](std::size_t f, std::size_t k) -> Vec3 {
    return m.observed.targets[m.observed.frames[f].first + k];
  };
  std::size_t f = static_cast<std::size_t>(std::upper_bound(ft.begin(), ft.end(), t) - ft.begin());
  f = std::min(std::max<std::size_t>(f, 1), ft.size() - 1);  // frames f-1 and f bracket t
  if (!full(f - 1) || !full(f)) return false;
  // Velocity at a frame: central difference where both neighbours are full
  // (second order), else one-sided.
  const auto velocity = [&](std::size_t g, std::size_t k) -> Vec3 {
    const std::size_t lo = g > 0 && full(g - 1) ? g - 1 : g;
    const std::size_t hi = g + 1 < ft.size() && full(g + 1) ? g + 1 : g;
    return (at(hi, k) - at(lo, k)) / (ft[hi] - ft[lo]);
  };
  const double w = (t - ft[f - 1]) / (ft[f] - ft[f - 1]);
  ClothState s(n);
  const ObservationPlan::Frame& first = m.observed.frames[f - 1];
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(m.observed.nodes[first.first + k]);
    s.set_position(i, (1 - w) * at(f - 1, k) + w * at(f, k));
    s.set_velocity(i, (1 - w) * velocity(f - 1, k) + w * velocity(f, k));
  }
  state = std::move(s);
  return true;
}

double FitProblem::rms_error(const Eigen::VectorXd& theta) {
  Impl& m = *impl_;
  m.apply(m.inside(theta));
  const double data = m.rollout->run(m.model, nullptr);
  return std::sqrt(2.0 * data / static_cast<double>(std::max<std::size_t>(1, observations())));
}

std::size_t FitProblem::observations() const {
  return impl_->rollout ? impl_->rollout->data_count() : 0;
}
bool FitProblem::fits_cloud() const {
  return !impl_->observed.clouds.empty();
}
double FitProblem::duration() const {
  return impl_->duration;
}
std::size_t FitProblem::peak_tape_bytes() const {
  return impl_->rollout->peak_tape_bytes();
}

Scene FitProblem::fitted_scene(const Eigen::VectorXd& theta_in) const {
  const Eigen::VectorXd theta = impl_->inside(theta_in);
  Scene s = impl_->scene;
  for (const Unknown& u : impl_->unknowns) {
    if (u.per_element) continue;
    const double t = theta[static_cast<Eigen::Index>(u.block.offset)];
    const double v = u.block.log_space ? std::exp(t) : t;
    // A family that followed the spring constant (< 0) was fitted with it and
    // follows it still; one with its own value keeps it unless fitted itself.
    if (u.block.name == "spring_constant") {
      s.material.spring_constant = v;
    } else if (u.block.name == "shear_constant") {
      s.material.shear_constant = v;
    } else if (u.block.name == "bend_constant") {
      s.material.bend_constant = v;
    } else if (u.target == Target::viscosity) {
      s.material.viscosity = v;
    } else if (u.target == Target::node_mass) {
      s.material.node_mass = v;
    } else if (u.target == Target::friction) {
      s.material.friction = v;
    } else if (u.target == Target::rest_length) {
      continue;  // a scene derives lengths from positions: they go to the side file
    } else if (u.target == Target::path) {
      set_path(s.modules[std::size_t(u.declaration)].spec, u, theta);
    } else if (u.target == Target::initial_velocity) {
      const auto o = static_cast<Eigen::Index>(u.block.offset);
      s.initial_velocity = Vec3(theta[o], theta[o + 1], theta[o + 2]);
    } else if (u.declaration >= 0) {
      set_spec_parameter(s.modules[static_cast<std::size_t>(u.declaration)].spec, u.id, v);
    }
  }
  if (impl_->words) {  // the material stays in words, at the fitted inputs
    const DerivedMaterial d = s.fuzzy_material->rules->derive(impl_->inputs_at(theta));
    s.fuzzy_material->inputs = impl_->inputs_at(theta);
    s.fuzzy_material->notes = d.report.notes;
    s.material = d.material;
  } else {
    s.fuzzy_material.reset();
  }
  return s;
}

std::vector<std::string> FitProblem::inputs_in_words(const Eigen::VectorXd& theta_in) const {
  const Eigen::VectorXd theta = impl_->inside(theta_in);
  std::vector<std::string> words;
  for (const Unknown& u : impl_->unknowns)
    if (u.target == Target::input)
      words.push_back(fuzzy::in_words(
          impl_->scene.fuzzy_material->rules->system().inputs[static_cast<std::size_t>(u.input)],
          theta[static_cast<Eigen::Index>(u.block.offset)]));
  return words;
}

const fuzzy::LinguisticVariable* FitProblem::input_variable(const FitBlock& block) const {
  for (const Unknown& u : impl_->unknowns)
    if (u.target == Target::input && u.block.offset == block.offset)
      return &impl_->scene.fuzzy_material->rules->system()
                  .inputs[static_cast<std::size_t>(u.input)];
  return nullptr;
}

MaterialWeights FitProblem::element_weights(const Eigen::VectorXd& theta) const {
  // Every weight, also for a family fit: the side file is written only when
  // they differ from what FITTED.json's material builds (fitted_output.h), as
  // they do for numbers fitted to a material in words (each node's mass
  // share came from the rule base).
  impl_->apply(impl_->inside(theta));
  const ClothNetwork& net = impl_->model.net;
  return {net.springs.stiffness, net.springs.damping, net.masses.inverse_mass, net.masses.friction};
}

std::vector<double> FitProblem::element_rest_lengths(const Eigen::VectorXd& theta) const {
  for (const Unknown& u : impl_->unknowns)
    if (u.target == Target::rest_length) {
      impl_->apply(impl_->inside(theta));
      return impl_->model.net.springs.rest_length;
    }
  return {};
}

}  // namespace neurocloth
