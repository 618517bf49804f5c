#pragma once
// The UI's own copy of every setting the panels show. Widgets bind to these,
// never to simulation fields; an edit becomes a command (SetParameter, ...).
// They follow the simulation's status only when it starts over (a scene loads
// or is reset): a slider being dragged is then never pulled back by a status
// that lags a few commands behind it.
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "runtime/simulation_thread.h"

namespace neurocloth {

struct UiValues {
  int integrator = 0;  // index into kAllIntegrators
  bool adaptive = false;
  double dt = 0, viscosity = 0, friction = 0;
  std::array<double, 3> gravity{0, -9.81, 0};
  bool has_wind = false;
  std::array<double, 3> wind{0, 0, 0};
  std::vector<std::pair<std::string, double>> inputs;  // linguistic, when fuzzy

  // The window's own settings (no simulation field behind them).
  // The mouse drag's pull per kg and metre, 1/s^2: stiff enough that a node
  // drags its neighbours along (4000 s^-2 is omega = 63 rad/s, below the
  // springs' own frequencies in the shipped scenes, so it adds no instability).
  double drag_gain = 4000;
  // The accuracy slider: the largest position error asked for, as a fraction of
  // the cloth's size, and what the last request picked (or why nothing).
  float accuracy = 0.01f;
  std::string accuracy_pick;

  // Text fields (ImGui edits plain char buffers).
  std::array<char, 512> scene_path{};
  std::array<char, 512> rules_path{};
  int preset = 0;  // index into preset_names()
  // The Scene panel's obstacle to add: an OBJ, its scale and where its origin goes.
  std::array<char, 512> obstacle_path{};
  float obstacle_scale = 1;
  std::array<float, 3> obstacle_translate{0, 0, 0};

  // Copies every setting from `status` when the run started over since the last call.
  void follow(const SimulationStatus& status);
  // Mirrors a value set through `id` (input and module ids index `names`);
  // false when no field shows it (only the first wind module's velocity has one).
  bool assign(const ParameterId& id, const ParameterNames& names, double value);
  double* field(const ParameterId& id, const ParameterNames& names);

 private:
  void copy_from(const SimulationStatus& status);
  std::string followed_path_;
  double followed_time_ = -1;
  bool followed_once_ = false;
};

// The value `id` has in `status`, if the status carries it.
std::optional<double> status_value(const SimulationStatus& status, const ParameterId& id,
                                   const ParameterNames& names);

void copy_text(std::array<char, 512>& buffer, const std::string& text);

}  // namespace neurocloth
