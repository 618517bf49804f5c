#include "runtime/live_scene.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <numeric>
#include <sstream>
#include <utility>

#include "core/integrators/stability.h"
#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "runtime/live_scene_run.h"

namespace neurocloth {

namespace live_detail {

std::string number(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

bool finite(const Vec3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

// The first wind module's declaration index, or -1: the one whose mean wind
// the status reports.
int first_wind(const ParameterNames& names) {
  for (std::size_t m = 0; m < names.modules.size(); ++m)
    if (names.modules[m] == "wind") return static_cast<int>(m);
  return -1;
}

// What the network uses for a per-spring or per-node weight: the value when all
// agree (as after a material or a SetParameter), else the mean (learned weights).
double typical(const std::vector<double>& v, double fallback) {
  if (v.empty()) return fallback;
  const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  if (*lo == *hi) return *lo;
  return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

// What a cloth may cost per dt while someone watches: about 2e7 spring
// updates (about 0.1 s of network steps), so that no advance() at the step's
// floor holds the thread — and with it pause, reset and every command — for seconds.
constexpr double kLiveSpringUpdatesPerDt = 2e7;

// The scene's simulation as the thread runs it: a fixed step above the
// stability bound is taken in substeps under it (a live change may make it
// so: a smaller mass, a stiffer material, more viscosity, another
// integrator), and the work per dt is bounded for the cloth's size.
Simulation live_simulation(Scene scene) {
  scene.solver.substep_above_cap = true;
  const double springs = std::max<double>(1.0, static_cast<double>(scene.topology.springs.size()));
  const long affordable = std::max(64L, static_cast<long>(kLiveSpringUpdatesPerDt / springs));
  scene.solver.step_budget = std::min(scene.solver.step_budget, affordable);
  return scene.make_simulation();
}

}  // namespace live_detail

using namespace live_detail;

LiveScene::LiveScene(Scene scene, bool paused) : paused_(paused) {
  start(std::make_unique<Run>(std::make_shared<const Scene>(std::move(scene))));
}

LiveScene::~LiveScene() = default;

Simulation& LiveScene::simulation() {
  return run_->sim;
}
const Simulation& LiveScene::simulation() const {
  return run_->sim;
}
const Scene& LiveScene::scene() const {
  return run_->scene;
}
const std::vector<ParameterRange>& LiveScene::ranges() const {
  return run_->ranges;
}
const ParameterNames& LiveScene::names() const {
  return run_->names;
}
const std::shared_ptr<const SceneGeometry>& LiveScene::geometry() const {
  return run_->geometry;
}

void LiveScene::start(std::unique_ptr<Run> run) {
  run_ = std::move(run);
  const Scene& s = run_->scene;
  viscosity_.reset();
  friction_.reset();
  fitted_.reset();
  inputs_.clear();
  if (s.fuzzy_material) inputs_ = s.fuzzy_material->inputs;
  wind_.reset();
  for (const ModuleDeclaration& m : s.modules)
    if (const auto* w = std::get_if<WindSpec>(&m.spec)) {
      wind_ = w->velocity;
      break;
    }
  forces_.clear();
  owed_ = 0;
  ++generation_;
}

std::string LiveScene::apply(const SimCommand& command) {
  // Anything a command throws (a file that will not read, a rule base that
  // does not fit) is its refusal; the run goes on as it was.
  try {
    return std::visit([this](const auto& c) { return on(c); }, command);
  } catch (const std::exception& e) {
    return e.what();
  }
}

Material LiveScene::target_material(const std::map<std::string, double>& inputs) const {
  const FuzzyMaterial* rules = run_->rules();
  Material m = fitted_ ? *fitted_ : rules ? rules->derive(inputs).material : run_->scene.material;
  if (viscosity_) m.viscosity = *viscosity_;
  if (friction_) m.friction = *friction_;
  return m;
}

std::string LiveScene::on(const SetParameter& c) {
  const ParameterRange* r = find_range(run_->ranges, c.id);
  const std::string name = to_string(c.id, run_->names);
  if (!r) {
    std::string known;
    for (const ParameterRange& p : run_->ranges)
      known += (known.empty() ? "" : ", ") + p.name;
    return "SetParameter: unknown parameter '" + name + "' (this scene has: " + known + ")";
  }
  if (!(c.value >= r->min && c.value <= r->max))  // NaN fails too
    return "SetParameter: " + name + " = " + number(c.value) + " is outside its range " +
           describe_range(*r);
  set_parameter(c.id, c.value);
  return {};
}

// `id` and `value` are checked against the ranges already.
void LiveScene::set_parameter(const ParameterId& id, double value) {
  Simulation& sim = run_->sim;
  using Kind = ParameterId::Kind;
  switch (id.kind) {
    case Kind::viscosity:
    case Kind::friction: {
      ClothNetwork& net = sim.mutable_network();
      if (id.kind == Kind::viscosity) {
        viscosity_ = value;
        std::fill(net.springs.damping.begin(), net.springs.damping.end(), value);
      } else {
        friction_ = value;
        std::fill(net.masses.friction.begin(), net.masses.friction.end(), value);
      }
      // A material ramp in progress would write its own value back: aim it at the new one.
      if (sim.ramping()) sim.ramp_to_material(target_material());
      break;
    }
    case Kind::dt: {
      SolverSettings s = sim.settings();
      s.dt = value;
      sim.set_solver_settings(s);
      break;
    }
    case Kind::gravity:
      sim.mutable_network().gravity[id.axis] = value;
      sim.rebase_divergence_check();  // the energy budget was for the old gravity
      break;
    case Kind::module:
      if (const int k = run_->force_module(id.index); k >= 0)
        sim.set_module_parameter(static_cast<std::size_t>(k), id, value);
      if (id.index == first_wind(run_->names) && id.parameter == ModuleParameter::velocity)
        (*wind_)[id.axis] = value;
      sim.rebase_divergence_check();  // and for the old forces
      break;
    case Kind::input: {
      std::map<std::string, double> inputs = inputs_;
      inputs[run_->names.inputs[id.index]] = value;
      // A new input asks the rule base again: an applied fit gives way.
      const std::optional<Material> fitted = std::exchange(fitted_, std::nullopt);
      try {
        sim.ramp_to_material(target_material(inputs));  // no jolt: the weights move over 64 steps
      } catch (...) {
        fitted_ = fitted;
        throw;
      }
      inputs_ = std::move(inputs);  // only once the ramp took it
      break;
    }
  }
}

std::string LiveScene::on(const SetIntegrator& c) {
  const bool known = std::find(std::begin(kAllIntegrators), std::end(kAllIntegrators), c.kind) !=
                     std::end(kAllIntegrators);
  if (!known)
    return "SetIntegrator: unknown integrator " + std::to_string(static_cast<int>(c.kind)) +
           " (expected one of: " + integrator_names() + ")";
  SolverSettings s = run_->sim.settings();
  s.integrator = c.kind;
  if (iterates_per_step(c.kind)) s.adaptive = false;  // it takes fixed steps
  run_->sim.set_solver_settings(s);
  return {};
}

std::string LiveScene::on(const SetAdaptive& c) {
  SolverSettings s = run_->sim.settings();
  s.adaptive = c.on;
  run_->sim.set_solver_settings(s);
  return {};
}

std::string LiveScene::on(const SetSolver& c) {
  if (const ParameterRange* r = find_range(run_->ranges, ParameterId::of(ParameterId::Kind::dt)))
    if (!(c.dt >= r->min && c.dt <= r->max))  // NaN fails too
      return "SetSolver: dt = " + number(c.dt) + " is outside its range " + describe_range(*r);
  SolverSettings s = run_->sim.settings();  // keeps the live run's budget and substep guard
  s.integrator = c.integrator;
  s.dt = c.dt;
  s.adaptive = c.adaptive;
  s.adaptive_settings.safety = c.safety;
  s.iterations = c.iterations;
  s.linear_tolerance = c.linear_tolerance;
  try {
    validate(s);
  } catch (const std::exception& e) {
    return std::string("SetSolver: ") + e.what();
  }
  run_->sim.set_solver_settings(s);
  return {};
}

std::string LiveScene::check_node(const char* command, int node) const {
  const std::size_t n = run_->sim.network().node_count();
  if (node >= 0 && static_cast<std::size_t>(node) < n) return {};
  return std::string(command) + ": node " + std::to_string(node) +
         " does not exist (the cloth has " + std::to_string(n) + " nodes, 0.." +
         std::to_string(static_cast<long>(n) - 1) + ")";
}

std::string LiveScene::on(const ApplyForce& c) {
  if (std::string why = check_node("ApplyForce", c.node); !why.empty()) return why;
  if (!finite(c.force) || !finite(c.anchor)) return "ApplyForce: force and anchor must be finite";
  run_->sim.set_external_force(static_cast<std::size_t>(c.node), c.force);
  auto same = [&](const FrameSnapshot::AppliedForce& f) { return f.node == c.node; };
  const auto it = std::find_if(forces_.begin(), forces_.end(), same);
  if (it != forces_.end())
    *it = {c.node, c.force, c.anchor};
  else
    forces_.push_back({c.node, c.force, c.anchor});
  return {};
}

// Releasing a node that is not pulled is not an error: a UI may send it on
// every mouse-up.
std::string LiveScene::on(const ReleaseForce& c) {
  if (std::string why = check_node("ReleaseForce", c.node); !why.empty()) return why;
  run_->sim.set_external_force(static_cast<std::size_t>(c.node), Vec3::Zero());
  forces_.erase(std::remove_if(forces_.begin(), forces_.end(),
                               [&](const auto& f) { return f.node == c.node; }),
                forces_.end());
  return {};
}

std::string LiveScene::on(const SetPinned& c) {
  if (std::string why = check_node("SetPinned", c.node); !why.empty()) return why;
  run_->sim.set_pinned(static_cast<std::size_t>(c.node), c.pinned);
  return {};
}

std::string LiveScene::on(const SetPaused& c) {
  paused_ = c.paused;
  owed_ = 0;
  return {};
}

std::string LiveScene::on(const SingleStep&) {
  Simulation& sim = run_->sim;
  if (!paused_) return "SingleStep: only while paused (the simulation is running)";
  if (sim.status() != RunStatus::ok)
    return "SingleStep: the run diverged (" + sim.divergence_reason() + "); Reset first";
  sim.advance(sim.settings().dt);
  // The full check after every stepping command, as after a published slice:
  // where the checks fall (and so which state a divergence rolls back to) then
  // depends on the commands alone, not on how the queue happened to be batched.
  sim.check_now();
  return {};
}

std::string LiveScene::on(const Advance& c) {
  // One Advance holds every other command until it is done (only the thread's
  // stop cuts it short): a frame asks for 1/60 s; more than a second is refused.
  constexpr double kLongestAdvance = 1.0;  // s
  if (!(c.seconds >= 0 && c.seconds <= kLongestAdvance))
    return "Advance: seconds must lie in [0, 1] (got " + number(c.seconds) + ")";
  Simulation& sim = run_->sim;
  // Paused or diverged, time stands still and nothing is owed (as a paused
  // realtime run owes nothing for the pause).
  if (paused_ || sim.status() != RunStatus::ok) {
    owed_ = 0;
    return {};
  }
  owed_ += c.seconds;
  const double dt = sim.settings().dt;
  // A step owed to within round-off is owed (1/60 s is no multiple of dt).
  const double steps = std::floor(owed_ / dt + 1e-9);
  if (steps < 1) return {};
  const double start = sim.time();
  if (stop_) sim.set_interrupt([this](const Simulation&) { return stop_(); });
  sim.advance(steps * dt);
  sim.set_interrupt({});
  sim.check_now();
  if (sim.interrupted()) {
    owed_ = 0;
    return "Advance: cut short at t = " + number(sim.time()) + " s (the thread is stopping)";
  }
  owed_ -= steps * dt;
  // Behind (a step budget that ran out, a divergence rolled back): the debt is
  // dropped, as a realtime run re-syncs, rather than chased frame after frame.
  if (sim.status() != RunStatus::ok || sim.time() < start + steps * dt - 1e-9 * dt) owed_ = 0;
  owed_ = std::max(owed_, 0.0);
  return {};
}

std::string LiveScene::on(const Reset&) {
  start(std::make_unique<Run>(std::make_shared<const Scene>(run_->scene)));
  return {};
}

std::string LiveScene::on(const LoadScene& c) {
  start(
      std::make_unique<Run>(c.scene ? c.scene : std::make_shared<const Scene>(load_scene(c.path))));
  return {};
}

void LiveScene::describe(SimulationStatus& s) {
  Simulation& sim = run_->sim;
  const ClothNetwork& net = sim.network();
  s.scene_name = run_->scene.name;
  s.scene_path = run_->scene.path;
  s.scene = run_->loaded;
  s.run = sim.status();
  s.divergence_reason = sim.divergence_reason();
  s.time = sim.time();
  s.steps = sim.steps();
  s.rejected_steps = sim.rejected_steps();
  s.step_cap = sim.step_cap();
  s.paused = paused_;
  s.integrator = sim.settings().integrator;
  s.adaptive = sim.settings().adaptive;
  s.dt = sim.settings().dt;
  s.viscosity = typical(net.springs.damping, viscosity_.value_or(run_->scene.material.viscosity));
  s.friction = typical(net.masses.friction, friction_.value_or(run_->scene.material.friction));
  s.gravity = net.gravity;
  s.wind = wind_;
  s.material_inputs.assign(inputs_.begin(), inputs_.end());
  s.modules = sim.module_reports();
  s.substeps = sim.substeps();
  s.step_budget_exhausted = sim.budget_exhausted();
}

std::string LiveScene::stability_notice() {
  Simulation& sim = run_->sim;
  const SolverSettings& s = sim.settings();
  const char* integrator = to_string(s.integrator);
  std::ostringstream os;
  os.precision(3);
  if (sim.budget_exhausted()) {
    os << "step budget reached: " << integrator << " needs steps of at most " << sim.step_cap()
       << " s on this cloth, more than " << s.step_budget << " per dt = " << s.dt
       << " s; the simulation falls behind (a softer or heavier material, or implicit_euler, "
          "needs fewer)";
    return os.str();
  }
  const long substeps = sim.substeps();
  const double step = s.adaptive ? sim.step_cap() : s.dt / static_cast<double>(substeps);
  if (s.integrator == IntegratorKind::explicit_euler) {
    // With viscosity the cap and the guard keep forward Euler below its damped
    // limit; without it no step is stable, and the user should know.
    const double limit = explicit_euler_step_bound(sim.network());
    if (step > limit) {
      os << "explicit_euler gains energy on this cloth at ";
      if (limit > 0.0)
        os << "steps above " << limit << " s (viscosity / stiffness)";
      else
        os << "every step (a spring without viscosity)";
      os << " and takes " << step
         << " s: expect a divergence (network, verlet, rk4 and implicit_euler do not)";
      return os.str();
    }
  }
  if (substeps > 1) {
    os << "dt = " << s.dt << " s is above the stable step of " << integrator << " on this cloth ("
       << sim.step_cap() << " s): each step runs as " << substeps
       << " substeps (a smaller dt does the same; implicit_euler takes dt in one step)";
    return os.str();
  }
  return {};
}

}  // namespace neurocloth
