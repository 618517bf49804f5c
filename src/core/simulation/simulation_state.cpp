// Bit-for-bit comparison of two run states, member by member, so a restore or
// a copy that lost one member is caught and named.
#include "core/simulation/simulation_state.h"

namespace neurocloth {

namespace {

bool same_module_states(const std::vector<Cloned<ModuleState>>& a,
                        const std::vector<Cloned<ModuleState>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t k = 0; k < a.size(); ++k) {
    if (bool(a[k]) != bool(b[k])) return false;
    if (a[k] && !a[k]->same_bits(*b[k])) return false;
  }
  return true;
}

}  // namespace

const char* to_string(RunStatus s) {
  return s == RunStatus::ok ? "ok" : "diverged";
}

std::string first_difference(const SimulationState& a, const SimulationState& b) {
  const StepCounters &ca = a.counters, &cb = b.counters;
  const std::pair<bool, const char*> members[] = {
      {a.current == b.current, "current"},
      {same_bits(a.buffers[0], b.buffers[0]), "buffers[0]"},
      {same_bits(a.buffers[1], b.buffers[1]), "buffers[1]"},
      {same_bits(a.time, b.time), "time"},
      {ca.steps == cb.steps, "counters.steps"},
      {ca.rejected == cb.rejected, "counters.rejected"},
      {ca.force_evaluations == cb.force_evaluations, "counters.force_evaluations"},
      {ca.cg_iterations == cb.cg_iterations, "counters.cg_iterations"},
      {ca.steps_since_check == cb.steps_since_check, "counters.steps_since_check"},
      {ca.degenerate_springs == cb.degenerate_springs, "counters.degenerate_springs"},
      {same_bits(a.inputs.external_force, b.inputs.external_force), "inputs.external_force"},
      {same_bits(a.inputs.time, b.inputs.time), "inputs.time"},
      {same_module_states(a.module_states, b.module_states), "module_states"},
      {same_bits(a.checkpoint.state, b.checkpoint.state), "checkpoint.state"},
      {same_bits(a.checkpoint.time, b.checkpoint.time), "checkpoint.time"},
      {a.checkpoint.steps == b.checkpoint.steps, "checkpoint.steps"},
      {a.status == b.status, "status"},
      {a.reason == b.reason, "reason"},
      {a.monitor.same_bits(b.monitor), "monitor"},
      {a.ramp.same_bits(b.ramp), "ramp"},
  };
  for (const auto& [same, name] : members)
    if (!same) return name;
  return {};
}

bool same_bits(const SimulationState& a, const SimulationState& b) {
  return first_difference(a, b).empty();
}

}  // namespace neurocloth
