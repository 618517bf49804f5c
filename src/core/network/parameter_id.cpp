#include "core/network/parameter_id.h"

#include <algorithm>

namespace neurocloth {

namespace {

// The module types that have live parameters, and what those are called in text.
struct LiveModuleParameter {
  const char* type;
  ModuleParameter parameter;
};
constexpr LiveModuleParameter kModuleParameters[] = {
    {"wind", ModuleParameter::velocity},
};

constexpr const char* kAxes[] = {"x", "y", "z"};

}  // namespace

// "wind" for the first module of its type, "wind[k]" for the k-th after it:
// a scene with one wind module (all the shipped ones) never shows an index.
std::string module_name(const ParameterNames& names, int index) {
  const std::string& type = names.modules[index];
  const auto same = std::count(names.modules.begin(), names.modules.begin() + index, type);
  return same == 0 ? type : type + "[" + std::to_string(same) + "]";
}

namespace {

bool valid(const std::vector<std::string>& list, int index) {
  return index >= 0 && static_cast<std::size_t>(index) < list.size();
}

}  // namespace

const char* module_parameter_name(ModuleParameter p) {
  switch (p) {
    case ModuleParameter::velocity:
      return "velocity";
    case ModuleParameter::rate:
      return "rate";
    case ModuleParameter::drag:
      return "drag";
    case ModuleParameter::lift:
      return "lift";
    case ModuleParameter::friction:
      return "friction";
    case ModuleParameter::rigidity:
      return "rigidity";
  }
  return "?";
}

// Fields a kind does not use take no part: gravity.x is gravity.x whatever its index says.
bool operator==(const ParameterId& a, const ParameterId& b) {
  if (a.kind != b.kind) return false;
  switch (a.kind) {
    case ParameterId::Kind::gravity:
      return a.axis == b.axis;
    case ParameterId::Kind::input:
      return a.index == b.index;
    case ParameterId::Kind::module:
      return a.index == b.index && a.parameter == b.parameter && a.axis == b.axis;
    default:
      return true;
  }
}

std::vector<ParameterId> all_parameters(const ParameterNames& names) {
  using Kind = ParameterId::Kind;
  std::vector<ParameterId> ids = {ParameterId::of(Kind::viscosity), ParameterId::of(Kind::friction),
                                  ParameterId::of(Kind::dt)};
  for (int axis = 0; axis < 3; ++axis)
    ids.push_back(ParameterId::gravity(axis));
  for (std::size_t i = 0; i < names.inputs.size(); ++i)
    ids.push_back(ParameterId::input(static_cast<int>(i)));
  for (std::size_t m = 0; m < names.modules.size(); ++m)
    for (const LiveModuleParameter& p : kModuleParameters)
      if (names.modules[m] == p.type)
        for (int axis = 0; axis < 3; ++axis)
          ids.push_back(ParameterId::module(static_cast<int>(m), p.parameter, axis));
  return ids;
}

// The names are few (tens): matching the text against each one's spelling
// keeps parsing and writing one definition, so they cannot disagree.
std::optional<ParameterId> parse_parameter(const std::string& text, const ParameterNames& names,
                                           std::string* why) {
  const std::vector<ParameterId> ids = all_parameters(names);
  for (const ParameterId& id : ids)
    if (to_string(id, names) == text) return id;
  if (why) {
    std::string known;
    for (const ParameterId& id : ids)
      known += (known.empty() ? "" : ", ") + to_string(id, names);
    *why = "unknown parameter '" + text + "' (this scene has: " + known + ")";
  }
  return std::nullopt;
}

std::string to_string(const ParameterId& id, const ParameterNames& names) {
  const bool axis = id.axis >= 0 && id.axis < 3;
  const std::string suffix = axis ? std::string(".") + kAxes[id.axis] : ".?";
  switch (id.kind) {
    case ParameterId::Kind::viscosity:
      return "viscosity";
    case ParameterId::Kind::friction:
      return "friction";
    case ParameterId::Kind::dt:
      return "dt";
    case ParameterId::Kind::gravity:
      return "gravity" + suffix;
    case ParameterId::Kind::input:
      if (!valid(names.inputs, id.index)) return "input#" + std::to_string(id.index);
      return "input." + names.inputs[id.index];
    case ParameterId::Kind::module:
      if (!valid(names.modules, id.index)) return "module#" + std::to_string(id.index);
      return module_name(names, id.index) + "." + module_parameter_name(id.parameter) +
             (id.parameter == ModuleParameter::velocity ? suffix : std::string());
  }
  return "?";
}

}  // namespace neurocloth
