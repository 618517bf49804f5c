// The numbers a user may change while the simulation runs, and their ranges:
// wide enough for any experiment the viewer invites, narrow enough that a typo
// (a viscosity of 5000, a dt of 2 s) is refused rather than run into a divergence.
#include <sstream>

#include "runtime/live_scene.h"

namespace neurocloth {

std::vector<ParameterRange> parameter_ranges(const Scene& scene) {
  const ParameterNames names = parameter_names(scene);
  const FuzzyMaterial* rules = scene.fuzzy_material ? scene.fuzzy_material->rules.get() : nullptr;
  std::vector<ParameterRange> r;
  for (const ParameterId& id : all_parameters(names)) {
    ParameterRange range{id, to_string(id, names), 0, 0, ""};
    switch (id.kind) {
      case ParameterId::Kind::viscosity:
        range = {id, range.name, 0, 100, "N s/m"};
        break;
      case ParameterId::Kind::friction:
        range = {id, range.name, 0, 5, ""};
        break;
      case ParameterId::Kind::dt:
        range = {id, range.name, 1e-5, 0.1, "s"};
        break;
      case ParameterId::Kind::gravity:
        range = {id, range.name, -100, 100, "m/s^2"};
        break;
      case ParameterId::Kind::input: {
        // A linguistic input may take any value its rule base defines terms over.
        const int i = rules ? rules->system().input_index(names.inputs[id.index]) : -1;
        if (i < 0) continue;
        const fuzzy::LinguisticVariable& v = rules->system().inputs[i];
        range = {id, range.name, v.min, v.max, ""};
        break;
      }
      case ParameterId::Kind::module:
        switch (id.parameter) {
          case ModuleParameter::velocity:
            range = {id, range.name, -50, 50, "m/s"};
            break;
          case ModuleParameter::rate:  // learning adapts these; they are no live control
          case ModuleParameter::drag:
          case ModuleParameter::lift:
          case ModuleParameter::friction:
          case ModuleParameter::rigidity:
            continue;
        }
        break;
    }
    r.push_back(std::move(range));
  }
  return r;
}

const ParameterRange* find_range(const std::vector<ParameterRange>& ranges, const ParameterId& id) {
  for (const ParameterRange& r : ranges)
    if (r.id == id) return &r;
  return nullptr;
}

std::string describe_range(const ParameterRange& range) {
  std::ostringstream os;
  os << "[" << range.min << ", " << range.max << "]";
  if (!range.unit.empty()) os << " " << range.unit;
  return os.str();
}

}  // namespace neurocloth
