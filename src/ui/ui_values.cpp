#include "ui_values.h"

#include <algorithm>
#include <cstring>

namespace neurocloth {

namespace {

// "gravity.y" -> 1; -1 when `name` is not prefix + ".x|y|z".
int axis_of(const std::string& name, const std::string& prefix) {
  if (name.size() != prefix.size() + 2 || name.compare(0, prefix.size(), prefix) != 0 ||
      name[prefix.size()] != '.')
    return -1;
  const char axis = name.back();
  return axis >= 'x' && axis <= 'z' ? axis - 'x' : -1;
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

double* UiValues::field(const std::string& name) {
  if (name == "viscosity") return &viscosity;
  if (name == "friction") return &friction;
  if (name == "dt") return &dt;
  if (const int k = axis_of(name, "gravity"); k >= 0) return &gravity[k];
  if (const int k = axis_of(name, "wind"); k >= 0) return &wind[k];
  if (name.rfind("input.", 0) == 0)
    for (auto& [input, v] : inputs)
      if (input == name.substr(6)) return &v;
  return nullptr;
}

bool UiValues::assign(const std::string& name, double value) {
  double* f = field(name);
  if (f) *f = value;
  return f != nullptr;
}

std::optional<double> status_value(const SimulationStatus& status, const std::string& name) {
  if (name == "viscosity") return status.viscosity;
  if (name == "friction") return status.friction;
  if (name == "dt") return status.dt;
  if (const int k = axis_of(name, "gravity"); k >= 0) return status.gravity[k];
  if (const int k = axis_of(name, "wind"); k >= 0 && status.wind) return (*status.wind)[k];
  if (name.rfind("input.", 0) == 0)
    for (const auto& [input, v] : status.material_inputs)
      if (input == name.substr(6)) return v;
  return std::nullopt;
}

void copy_text(std::array<char, 512>& buffer, const std::string& text) {
  const std::size_t n = std::min(text.size(), buffer.size() - 1);
  std::memcpy(buffer.data(), text.data(), n);
  buffer[n] = '\0';
}

}  // namespace neurocloth
