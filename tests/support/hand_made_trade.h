#pragma once
// Hand-made trades for the tradeoff tests: rows whose costs and errors are
// chosen so the Pareto front, the picks and the ties are known by construction.
#include <limits>
#include <string>
#include <vector>

#include "tradeoff/trade_table.h"

namespace neurocloth::test {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

inline TradeRow row(const std::string& method, double cost, double error,
                    const std::string& status = "ok") {
  TradeRow r;
  r.method = method;
  r.parameter = method == kAdaptiveMethod ? "safety" : "dt";
  r.value = r.dt = 0.001;
  r.wall_per_simulated_second = cost;
  r.position_error_max = error;
  r.position_error_rms = error / 4;
  r.status = status;
  return r;
}

inline std::vector<TradeRow> hand_made() {
  return {row("network", 1, 0.1),                        // 0: front
          row("verlet", 2, 0.01),                        // 1: front
          row("rk4", 3, 0.05),                           // 2: beaten by 1
          row("explicit_euler", 0.5, 0.5),               // 3: front (cheapest)
          row("explicit_euler", 0.1, kNaN, "diverged"),  // 4: not finished
          row("implicit_euler", 2, 0.01),                // 5: ties with 1: both on the front
          row("rk4", 4, 0.001),                          // 6: front
          row("adaptive", 4, 0.002)};                    // 7: beaten by 6 (same cost, larger error)
}

inline TradeTable hand_made_trade() {
  TradeTable t;
  t.scene = "hand";
  t.seconds = 2;
  t.samples = 8;
  t.reference.change = 1e-10;
  t.reference.met = true;
  t.rows = hand_made();
  t.rows[7].value = 0.25;
  return t;
}

// A trade of the shipped `hanging` scene over 0.5 s with a converged
// reference and no rows yet: what the command-line tests add their rows to.
inline TradeTable hanging_trade(const std::string& scene = "hanging") {
  TradeTable t;
  t.scene = scene;
  t.scene_file = "assets/scenes/hanging.json";
  t.seconds = 0.5;
  t.samples = 4;
  t.cloth_size = 1.34;
  t.energy_scale = 52;
  t.reference.dt = 1e-4;
  t.reference.change = 1e-10;
  t.reference.met = true;
  t.reference.stopped_by = "target";
  return t;
}

}  // namespace neurocloth::test
