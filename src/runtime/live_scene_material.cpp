// What changes the running scene's material from outside: a new rule base
// (LoadRules) and an applied fit (ApplyFit). Both ramp the weights over 64
// steps, as a slider does, and refuse whole what they cannot take.
#include <cmath>
#include <map>
#include <string>
#include <utility>

#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "core/network/material_limits.h"
#include "runtime/live_scene_run.h"

namespace neurocloth {
using namespace live_detail;

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

}  // namespace neurocloth
