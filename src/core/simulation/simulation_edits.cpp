// Building a simulation and changing it between steps: the constructor, live
// edits of the model (weights, modules, settings, pins, a ramp to a new
// material), setting or restoring the state, and reports. Every edit is
// checked before anything changes, and says what it leaves stale; stepping
// is in simulation.cpp.
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "core/simulation/simulation.h"

namespace neurocloth {

namespace {

// Bad input is refused before anything changes, with the field it is in.
[[noreturn]] void refuse(const std::string& field, std::size_t index, const char* rule,
                         double value) {
  std::ostringstream os;
  os << field << "[" << index << "] must be " << rule << ", got " << value;
  throw std::invalid_argument(os.str());
}

void check_state(const ClothState& s, const char* what) {
  if (s.all_finite()) return;
  for (std::size_t i = 0; i < s.size(); ++i)
    if (!s.position(i).allFinite() || !s.velocity(i).allFinite())
      throw std::invalid_argument(std::string(what) + ": node " + std::to_string(i) +
                                  " has a non-finite position or velocity");
}

// The weights a step divides by or multiplies with: finite, a positive inverse
// mass, no negative stiffness or damping (either would pump energy in).
void check_weights(const std::vector<double>& stiffness, const std::vector<double>& damping,
                   const std::vector<double>& inverse_mass) {
  for (std::size_t i = 0; i < stiffness.size(); ++i)
    if (!(stiffness[i] >= 0 && std::isfinite(stiffness[i])))
      refuse("springs.stiffness", i, "finite and >= 0", stiffness[i]);
  for (std::size_t i = 0; i < damping.size(); ++i)
    if (!(damping[i] >= 0 && std::isfinite(damping[i])))
      refuse("springs.damping", i, "finite and >= 0", damping[i]);
  for (std::size_t i = 0; i < inverse_mass.size(); ++i)
    if (!(inverse_mass[i] > 0 && std::isfinite(inverse_mass[i])))
      refuse("masses.inverse_mass", i, "finite and > 0 (a node needs a mass)", inverse_mass[i]);
}

void check_weights(const ClothNetwork& net) {
  check_weights(net.springs.stiffness, net.springs.damping, net.masses.inverse_mass);
  if (!net.gravity.allFinite()) refuse("gravity", 0, "finite", net.gravity.norm());
}

// The settings a force evaluation reads from its context: the spring layer's
// arithmetic and the kernel that evaluates it.
void set_spring_arithmetic(ForceContext& context, const SolverSettings& s) {
  context.precision = s.precision;
  context.kernel = s.kernel;
  context.spring_damping = s.damping == DampingMode::explicit_force;
}

const SolverSettings& validated(const SolverSettings& s) {
  validate(s);
  return s;
}

// A saved state fits this simulation only with as many nodes (in every buffer)
// and as many constraint states; the message says which count differs.
void check_fits(const SimulationState& s, std::size_t nodes, std::size_t constraints) {
  auto refuse_count = [](const char* what, std::size_t got, std::size_t want) {
    std::ostringstream os;
    os << "restore: the state's " << what << " has " << got << ", this simulation's " << want;
    throw std::invalid_argument(os.str());
  };
  if (s.current != 0 && s.current != 1)
    throw std::invalid_argument("restore: the state's current buffer must be 0 or 1");
  for (const ClothState* c : {&s.buffers[0], &s.buffers[1], &s.checkpoint.state})
    if (c->size() != nodes) refuse_count("cloth (node count)", c->size(), nodes);
  const std::size_t ext = s.inputs.external_force.size();
  if (ext != 0 && ext != nodes) refuse_count("external force (node count)", ext, nodes);
  if (s.module_states.size() != constraints)
    refuse_count("constraint module states (module count)", s.module_states.size(), constraints);
}

}  // namespace

Simulation::Simulation(ClothNetwork network, ClothState initial, SolverSettings settings,
                       std::vector<std::shared_ptr<const ConstraintModule>> constraints)
    : net_(std::move(network)),
      constraints_(std::move(constraints)),
      settings_(validated(settings)),  // before the integrator is made from them
      integrator_(make_integrator(settings, net_)) {
  if (initial.size() != net_.node_count())
    throw std::invalid_argument("state size differs from the network's");
  check_state(initial, "initial state");
  check_weights(net_);
  for (std::size_t i = 0; i < net_.node_count(); ++i)
    if (net_.masses.free[i] != 0.0)
      force_scale_ = std::max(force_scale_, std::abs(net_.mass(i)) * net_.gravity.norm());
  if (force_scale_ == 0.0) force_scale_ = 1e-9;

  run_.buffers = {initial, initial};
  run_.checkpoint.state = initial;
  run_.monitor = DivergenceMonitor(net_, initial, settings_.divergence);
  for (const auto& c : constraints_)
    run_.module_states.push_back(c->make_state());

  ctx_.threads = OwnedStepThreads(settings_.threads);
  ctx_.force.clocks.resize(net_.force_modules.size());
  set_spring_arithmetic(ctx_.force, settings_);
  ctx_.constraint_clocks.resize(constraints_.size());
  ctx_.forces = {NodeVectors(net_.node_count()), NodeVectors(net_.node_count())};
  ctx_.step_start.resize(constraints_.empty() || !integrator_->steps_in_place() ? 0
                                                                                : initial.size());
}

ClothNetwork& Simulation::mutable_network() {
  invalidate(Stale::weights);
  return net_;
}

bool Simulation::set_module_parameter(std::size_t index, const ParameterId& id, double value) {
  if (index >= net_.force_modules.size()) throw std::out_of_range("no such force module");
  std::shared_ptr<ForceModule> changed = net_.force_modules[index]->clone();
  if (!changed->set_parameter(id, value)) return false;
  net_.force_modules[index] = std::move(changed);
  invalidate(Stale::forces);
  return true;
}

// The stability bound does not depend on external forces: only the cached
// forces are dropped.
void Simulation::set_external_force(std::size_t node, const Vec3& f) {
  if (node >= net_.node_count()) throw std::out_of_range("set_external_force: no such node");
  if (!f.allFinite()) throw std::invalid_argument("set_external_force: force must be finite");
  NodeVectors& ext = run_.inputs.external_force;
  if (ext.size() == 0) {
    if (f == Vec3::Zero()) return;  // nothing to add: no memory, no work
    ext.resize(net_.node_count());
  }
  ext.x[node] = f.x();
  ext.y[node] = f.y();
  ext.z[node] = f.z();
  invalidate(Stale::forces);
}

void Simulation::set_state(const ClothState& s) {
  if (s.size() != net_.node_count())
    throw std::invalid_argument("state size differs from the network's");
  check_state(s, "set_state");
  run_.cloth() = s;
  run_.checkpoint = {s, run_.time, run_.counters.steps};
  invalidate(Stale::forces);
}

void Simulation::restore(const SimulationState& s) {
  check_fits(s, net_.node_count(), constraints_.size());
  run_ = s;
  invalidate(Stale::weights);
}

void Simulation::set_solver_settings(const SolverSettings& settings) {
  validate(settings);  // before anything changes
  // Made before anything changes too: an integrator may refuse this cloth.
  std::unique_ptr<Integrator> integrator = make_integrator(settings, net_);
  settings_ = settings;
  set_spring_arithmetic(ctx_.force, settings_);
  if (ctx_.threads.size() != settings_.threads) ctx_.threads = OwnedStepThreads(settings_.threads);
  integrator_ = std::move(integrator);
  ctx_.step_start.resize(
      constraints_.empty() || !integrator_->steps_in_place() ? 0 : net_.node_count());
  invalidate(Stale::weights);
}

void Simulation::set_pinned(std::size_t node, bool pinned) {
  if (node >= net_.node_count()) throw std::out_of_range("no such node");
  mutable_network().set_pinned(node, pinned);
  if (!pinned) return;
  run_.cloth().set_velocity(node, Vec3::Zero());
  run_.checkpoint.state.set_velocity(node, Vec3::Zero());
}

void Simulation::rebase_divergence_check() {
  run_.monitor = DivergenceMonitor(net_, state(), settings_.divergence);
}

void Simulation::ramp_to_material(const Material& material, int steps) {
  const MaterialWeights target = net_.material_weights(material);
  // A bad material is refused; the ramp in progress goes on.
  check_weights(target.stiffness, target.damping, target.inverse_mass);
  run_.ramp.start(net_, target, steps);
}

std::size_t Simulation::module_overhead_bytes() const {
  return net_.force_modules.capacity() * sizeof(net_.force_modules[0]) +
         constraints_.capacity() * sizeof(constraints_[0]) +
         run_.module_states.capacity() * sizeof(run_.module_states[0]) +
         ctx_.force.clocks.capacity() * sizeof(ModuleClock) +
         ctx_.constraint_clocks.capacity() * sizeof(ModuleClock) +
         ctx_.step_start.allocated_bytes();
}

std::vector<ModuleReport> Simulation::module_reports() const {
  std::vector<ModuleReport> out;
  for (std::size_t k = 0; k < net_.force_modules.size(); ++k) {
    const ForceModule& m = *net_.force_modules[k];
    const ModuleClock& c = ctx_.force.clocks[k];
    out.push_back({m.type(), m.declaration, c.seconds, c.calls, m.state_bytes()});
  }
  for (std::size_t k = 0; k < constraints_.size(); ++k) {
    const ConstraintModule& m = *constraints_[k];
    const ModuleClock& c = ctx_.constraint_clocks[k];
    const std::size_t state = run_.module_states[k] ? run_.module_states[k]->bytes() : 0;
    out.push_back({m.type(), m.declaration, c.seconds, c.calls, m.state_bytes() + state});
  }
  return out;
}

}  // namespace neurocloth
