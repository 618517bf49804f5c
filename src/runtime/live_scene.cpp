#include "live_scene.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <numeric>
#include <sstream>
#include <utility>

#include "input_error.h"
#include "physical_limits.h"
#include "stability.h"

namespace neurocloth {

namespace {

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

}  // namespace

// Built in one piece so that a scene that fails to load or build replaces
// nothing.
struct LiveScene::Run {
  // The scene as it was loaded, shared with whoever asks (the UI builds its
  // view of the scene from it, not from the file again).
  std::shared_ptr<const Scene> loaded;
  Scene scene;  // what runs: LoadRules replaces its rule base
  Simulation sim;
  ParameterNames names;
  std::vector<ParameterRange> ranges;
  std::shared_ptr<const SceneGeometry> geometry;

  explicit Run(std::shared_ptr<const Scene> s)
      : loaded(std::move(s)),
        scene(*loaded),
        sim(live_simulation(scene)),
        names(parameter_names(scene)),
        ranges(parameter_ranges(scene)),
        geometry(make_geometry(scene)) {}

  const FuzzyMaterial* rules() const {
    return scene.fuzzy_material ? scene.fuzzy_material->rules.get() : nullptr;
  }

  // The module the scene declared `index`-th (a force module: only those have
  // live parameters), found as the same occurrence of its type among the
  // network's force modules, which keep the declaration order.
  // Its position in the network's force modules, or -1.
  int force_module(int index) const {
    const std::string& type = names.modules[index];
    auto occurrence = std::count(names.modules.begin(), names.modules.begin() + index, type);
    const auto& modules = sim.network().force_modules;
    for (std::size_t k = 0; k < modules.size(); ++k)
      if (modules[k]->type() == type && occurrence-- == 0) return static_cast<int>(k);
    return -1;
  }
};

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
  // One Advance holds every other command (and the thread's stop) until it is
  // done: a frame asks for 1/60 s; more than a second is refused.
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
  sim.advance(steps * dt);
  sim.check_now();
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

// The new rule base replaces the scene's: Reset then starts from the scene's
// inputs under it. It must take the same inputs, and the current values must lie
// in its ranges (the thread never lets an input be clamped silently).
std::string LiveScene::on(const LoadRules& c) {
  Scene& scene = run_->scene;
  if (!run_->rules())
    return "LoadRules: scene '" + scene.name +
           "' gives its material as numbers; only a scene whose material is a rule base can "
           "take new rules";
  const std::shared_ptr<const FuzzyMaterial> given =
      c.rules ? c.rules : std::make_shared<const FuzzyMaterial>(FuzzyMaterial::load(c.path));
  const FuzzyMaterial& rules = *given;
  for (const fuzzy::LinguisticVariable& v : rules.system().inputs) {
    const auto it = inputs_.find(v.name);
    if (it != inputs_.end() && !(it->second >= v.min && it->second <= v.max))
      throw InputError(c.path, "FUZZIFY " + v.name,
                       "the current value " + number(it->second) + " is outside its RANGE [" +
                           number(v.min) + ", " + number(v.max) + "]");
  }
  const DerivedMaterial now = rules.derive(inputs_, c.path, "input");  // same names, or throws
  const DerivedMaterial initial = rules.derive(scene.fuzzy_material->inputs, c.path, "input");
  for (const DerivedMaterial* d : {&now, &initial})  // as a scene file's rule base is checked
    if (const auto why = material_outside_limits(d->material))
      throw InputError(c.path, "", "the rule base gives " + *why);
  scene.material = initial.material;
  scene.fuzzy_material->rules_path = c.path;
  scene.fuzzy_material->rules = given;
  scene.fuzzy_material->notes = initial.report.notes;
  run_->ranges = parameter_ranges(scene);
  Material target = now.material;
  if (viscosity_) target.viscosity = *viscosity_;
  if (friction_) target.friction = *friction_;
  run_->sim.ramp_to_material(target);
  return {};
}

// Everything is checked before anything changes: a refused fit leaves the run as it was.
std::string LiveScene::on(const ApplyFit& c) {
  const Material& m = c.material;
  for (const double v :
       {m.spring_constant, m.shear_constant, m.bend_constant, m.node_mass, m.viscosity, m.friction})
    if (!std::isfinite(v)) return "ApplyFit: the fitted material has a value that is not finite";
  if (const auto why = material_outside_limits(m))
    return "ApplyFit: the fitted material has " + *why;
  std::vector<std::pair<int, const std::pair<ParameterId, double>*>> modules;
  for (const auto& p : c.module_parameters) {
    const ParameterId& id = p.first;
    const bool known = id.kind == ParameterId::Kind::module && id.index >= 0 &&
                       static_cast<std::size_t>(id.index) < run_->names.modules.size();
    if (!known) return "ApplyFit: no module parameter " + to_string(id, run_->names) + " here";
    const std::string name = to_string(id, run_->names);
    if (!std::isfinite(p.second))
      return "ApplyFit: " + name + " = " + number(p.second) + " is not finite";
    const int k = run_->force_module(id.index);
    if (k < 0)
      return "ApplyFit: " + name +
             " cannot change while the cloth runs (only force modules take live changes)";
    modules.push_back({k, &p});
  }
  // Fitted inputs: the rule base gives the material, as a slider's would.
  std::map<std::string, double> inputs = inputs_;
  for (const auto& [id, value] : c.inputs) {
    const bool known = id.kind == ParameterId::Kind::input && id.index >= 0 &&
                       static_cast<std::size_t>(id.index) < run_->names.inputs.size();
    if (!known || !run_->rules())
      return "ApplyFit: no input " + to_string(id, run_->names) + " here";
    if (!std::isfinite(value))
      return "ApplyFit: " + to_string(id, run_->names) + " = " + number(value) + " is not finite";
    inputs[run_->names.inputs[static_cast<std::size_t>(id.index)]] = value;
  }
  const Material target =
      c.inputs.empty() ? m : run_->rules()->derive(inputs, "the fit", "input").material;
  if (const auto why = material_outside_limits(target))
    return "ApplyFit: the fitted inputs give " + *why;
  Simulation& sim = run_->sim;
  for (const auto& [k, p] : modules)
    if (!sim.set_module_parameter(static_cast<std::size_t>(k), p->first, p->second))
      return "ApplyFit: module " + to_string(p->first, run_->names) + " refused the value";
  for (const auto& [k, p] : modules)
    if (p->first.index == first_wind(run_->names) &&
        p->first.parameter == ModuleParameter::velocity)
      (*wind_)[p->first.axis] = p->second;
  if (!modules.empty()) sim.rebase_divergence_check();  // the energy budget was for the old forces
  if (c.inputs.empty()) {
    fitted_ = m;
  } else {
    fitted_.reset();  // the material stays in words, at the fitted inputs
    inputs_ = std::move(inputs);
  }
  viscosity_.reset();  // the fit's own values, not the user's, from now on
  friction_.reset();
  sim.ramp_to_material(target_material());
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
