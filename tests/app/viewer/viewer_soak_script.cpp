#include "app/viewer/viewer_soak_script.h"

#include <algorithm>
#include <cmath>

namespace neurocloth {

namespace {

using nlohmann::json;

// A parameter's value: mostly plausible, sometimes at or far beyond any range.
// (JSON has no NaN or infinity: those reach the thread in its own soak.)
double random_value(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(0, 1);
  const double r = u(rng);
  if (r < 0.55) return std::uniform_real_distribution<double>(-20, 20)(rng);
  if (r < 0.7) return std::uniform_real_distribution<double>(1e-5, 0.1)(rng);  // a dt
  constexpr double kOdd[] = {0, 1e-5, 0.1, 1, 5, 100, -100, 50, -50, 1e300, -1e300, 1e-300, 1e9};
  return kOdd[std::uniform_int_distribution<std::size_t>(0, std::size(kOdd) - 1)(rng)];
}

template <class T>
const T& pick(std::mt19937_64& rng, const std::vector<T>& v) {
  return v[std::uniform_int_distribution<std::size_t>(0, v.size() - 1)(rng)];
}

json mods(std::mt19937_64& rng) {
  static const std::vector<std::string> kMods = {"shift", "ctrl", "alt"};
  json list = json::array();
  if (std::uniform_int_distribution<int>(0, 4)(rng) == 0) list.push_back(pick(rng, kMods));
  return list;
}

}  // namespace

json random_soak_script(std::mt19937_64& rng, double seconds, const SoakFiles& files) {
  static const std::vector<std::string> kButtons = {"left", "left", "left", "right", "middle"};
  static const std::vector<std::string> kKeys = {"space", "n", "f", "r",     "p", "F12",
                                                 "tab",   "1", "z", "enter", "F3"};
  static const std::vector<std::string> kNames = {
      "viscosity",       "friction",         "dt",
      "gravity.x",       "gravity.y",        "gravity.z",
      "wind.velocity.x", "wind.velocity.y",  "wind.velocity.z",
      "input.mass",      "input.elasticity", "input.force",
      "accuracy",        "no.such",          "input.no_such"};
  std::uniform_real_distribution<double> u(0, 1);
  std::exponential_distribution<double> gap(1 / 0.08);  // 12 events a second on average
  int width = 1280, height = 720, shots = 0;
  json events = json::array();
  for (double t = 0.05; t < seconds; t += gap(rng)) {
    json e = {{"t", t}};
    const int k = std::uniform_int_distribution<int>(0, 99)(rng);
    // Mostly inside the window (the cloth is in the middle), sometimes outside it.
    const double x = std::uniform_real_distribution<double>(-50, width + 50)(rng);
    const double y = std::uniform_real_distribution<double>(-50, height + 50)(rng);
    if (k < 28) {
      e.update({{"type", "move"}, {"x", x}, {"y", y}});
      if (u(rng) < 0.6) e["duration"] = 0.5 * u(rng);
    } else if (k < 46) {
      e.update({{"type", u(rng) < 0.55 ? "press" : "release"}, {"button", pick(rng, kButtons)}});
      const json m = mods(rng);
      if (!m.empty()) e["mods"] = m;
    } else if (k < 50) {
      e.update({{"type", "scroll"}, {"steps", std::round(10 * u(rng) - 5)}});
    } else if (k < 56) {
      e.update({{"type", "key"}, {"key", pick(rng, kKeys)}});
    } else if (k < 74) {
      const std::string& name = pick(rng, kNames);
      const double value = name == "accuracy" ? std::pow(10.0, -7 * u(rng)) : random_value(rng);
      e.update({{"type", "set"}, {"name", name}, {"value", value}});
    } else if (k < 84) {
      e.update({{"type", "probe"}, {"node", std::uniform_int_distribution<int>(0, 1100)(rng)}});
    } else if (k < 89) {
      // Minimised now and then, tiny, and larger than the screen.
      const int r = std::uniform_int_distribution<int>(0, 3)(rng);
      width = r == 0 ? 0 : r == 1 ? 64 : std::uniform_int_distribution<int>(200, 2000)(rng);
      height = r == 0 ? 0 : r == 1 ? 64 : std::uniform_int_distribution<int>(150, 1200)(rng);
      e.update({{"type", "resize"}, {"width", width}, {"height", height}});
      if (width == 0) width = 1280, height = 720;  // the cursor still roams the old area
    } else if (k < 93) {
      e.update({{"type", "load"}, {"path", pick(rng, files.scenes)}});
    } else if (k < 97) {
      e.update({{"type", "rules"}, {"path", pick(rng, files.rules)}});
    } else {
      e.update({{"type", "screenshot"},
                {"path", files.screenshot_prefix + std::to_string(shots++) + ".png"},
                {"panels", u(rng) < 0.5}});
    }
    events.push_back(std::move(e));
  }
  events.push_back({{"t", seconds}, {"type", "quit"}});
  return {{"description", "viewer_soak: random input (tests/app/viewer/viewer_soak_script.cpp)"},
          {"events", events}};
}

}  // namespace neurocloth
