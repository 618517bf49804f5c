#include "ui/ui_values.h"

#include <algorithm>
#include <cstring>

namespace neurocloth {

namespace {

// The status and the Forces panel show one wind: the scene's first wind module's.
bool is_shown_wind(const ParameterId& id, const ParameterNames& names) {
  if (id.kind != ParameterId::Kind::module || id.parameter != ModuleParameter::velocity)
    return false;
  const auto first = std::find(names.modules.begin(), names.modules.end(), "wind");
  return first != names.modules.end() && id.index == first - names.modules.begin();
}

// The input `id` names, "" when it names none.
std::string input_name(const ParameterId& id, const ParameterNames& names) {
  if (id.kind != ParameterId::Kind::input || id.index < 0 ||
      static_cast<std::size_t>(id.index) >= names.inputs.size())
    return "";
  return names.inputs[id.index];
}

int integrator_index(IntegratorKind kind) {
  for (std::size_t i = 0; i < std::size(kAllIntegrators); ++i)
    if (kAllIntegrators[i] == kind) return static_cast<int>(i);
  return 0;
}

bool same_names(const std::vector<std::pair<std::string, double>>& a,
                const std::vector<std::pair<std::string, double>>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].first != b[i].first) return false;
  return true;
}

}  // namespace

void UiValues::follow(const SimulationStatus& status) {
  // A new scene, or time running backwards (a reset), means the run started over.
  const bool restarted =
      !followed_once_ || status.scene_path != followed_path_ || status.time < followed_time_;
  if (restarted) copy_from(status);
  // A new rule base brings other inputs: take them as they are now.
  if (!same_names(inputs, status.material_inputs)) inputs = status.material_inputs;
  followed_once_ = true;
  followed_path_ = status.scene_path;
  followed_time_ = status.time;
}

void UiValues::copy_from(const SimulationStatus& status) {
  integrator = integrator_index(status.integrator);
  adaptive = status.adaptive;
  dt = status.dt;
  viscosity = status.viscosity;
  friction = status.friction;
  for (int k = 0; k < 3; ++k)
    gravity[k] = status.gravity[k];
  has_wind = status.wind.has_value();
  for (int k = 0; k < 3; ++k)
    wind[k] = has_wind ? (*status.wind)[k] : 0.0;
  inputs = status.material_inputs;
  if (scene_path[0] == '\0') copy_text(scene_path, status.scene_path);
}

double* UiValues::field(const ParameterId& id, const ParameterNames& names) {
  const bool axis = id.axis >= 0 && id.axis < 3;
  switch (id.kind) {
    case ParameterId::Kind::viscosity:
      return &viscosity;
    case ParameterId::Kind::friction:
      return &friction;
    case ParameterId::Kind::dt:
      return &dt;
    case ParameterId::Kind::gravity:
      return axis ? &gravity[id.axis] : nullptr;
    case ParameterId::Kind::module:
      return axis && is_shown_wind(id, names) ? &wind[id.axis] : nullptr;
    case ParameterId::Kind::input:
      for (auto& [input, v] : inputs)
        if (input == input_name(id, names)) return &v;
      return nullptr;
  }
  return nullptr;
}

bool UiValues::assign(const ParameterId& id, const ParameterNames& names, double value) {
  double* f = field(id, names);
  if (f) *f = value;
  return f != nullptr;
}

std::optional<double> status_value(const SimulationStatus& status, const ParameterId& id,
                                   const ParameterNames& names) {
  const bool axis = id.axis >= 0 && id.axis < 3;
  switch (id.kind) {
    case ParameterId::Kind::viscosity:
      return status.viscosity;
    case ParameterId::Kind::friction:
      return status.friction;
    case ParameterId::Kind::dt:
      return status.dt;
    case ParameterId::Kind::gravity:
      if (axis) return status.gravity[id.axis];
      return std::nullopt;
    case ParameterId::Kind::module:
      if (axis && status.wind && is_shown_wind(id, names)) return (*status.wind)[id.axis];
      return std::nullopt;
    case ParameterId::Kind::input:
      for (const auto& [input, v] : status.material_inputs)
        if (input == input_name(id, names)) return v;
      return std::nullopt;
  }
  return std::nullopt;
}

void copy_text(std::array<char, 512>& buffer, const std::string& text) {
  const std::size_t n = std::min(text.size(), buffer.size() - 1);
  std::memcpy(buffer.data(), text.data(), n);
  buffer[n] = '\0';
}

}  // namespace neurocloth
