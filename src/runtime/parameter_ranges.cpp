// The numbers a user may change while the simulation runs, and their ranges:
// wide enough for any experiment the viewer invites, narrow enough that a typo
// (a viscosity of 5000, a dt of 2 s) is refused rather than run into a divergence.
#include <sstream>
#include <type_traits>

#include "live_scene.h"

namespace neurocloth {

namespace {
bool has_wind(const Scene& scene) {
  for (const ModuleDeclaration& m : scene.modules)
    if (std::holds_alternative<WindSpec>(m.spec)) return true;
  return false;
}
}  // namespace

std::vector<ParameterRange> parameter_ranges(const Scene& scene, const FuzzyMaterial* rules) {
  std::vector<ParameterRange> r = {
      {"viscosity", 0, 100, "N s/m"}, {"friction", 0, 5, ""}, {"dt", 1e-5, 0.1, "s"}};
  for (const char* axis : {"x", "y", "z"})
    r.push_back({std::string("gravity.") + axis, -100, 100, "m/s^2"});
  if (has_wind(scene))
    for (const char* axis : {"x", "y", "z"})
      r.push_back({std::string("wind.") + axis, -50, 50, "m/s"});
  // A linguistic input may take any value its rule base defines terms over.
  if (rules)
    for (const fuzzy::LinguisticVariable& v : rules->system().inputs)
      r.push_back({"input." + v.name, v.min, v.max, ""});
  return r;
}

std::vector<ParameterRange> parameter_ranges(const Scene& scene) {
  if (!scene.fuzzy_material) return parameter_ranges(scene, nullptr);
  const FuzzyMaterial rules = FuzzyMaterial::load(scene.fuzzy_material->rules_path);
  return parameter_ranges(scene, &rules);
}

const ParameterRange* find_range(const std::vector<ParameterRange>& ranges,
                                 const std::string& name) {
  for (const ParameterRange& r : ranges)
    if (r.name == name) return &r;
  return nullptr;
}

std::string describe_range(const ParameterRange& range) {
  std::ostringstream os;
  os << "[" << range.min << ", " << range.max << "]";
  if (!range.unit.empty()) os << " " << range.unit;
  return os.str();
}

}  // namespace neurocloth
