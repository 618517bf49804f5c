#pragma once
// A measured trade between speed and accuracy on one scene: every setting tried
// (an integrator at a fixed step, or the paper's adaptive propagation at a
// safety factor), what it cost per simulated second and how far it landed from
// the converged reference. The tradeoff command writes it (trade_csv.h);
// `simulate --accuracy` and the viewer pick from it (accuracy_choice.h).
#include <optional>
#include <string>
#include <vector>

#include "core/simulation/solver_settings.h"
#include "tradeoff/converged_reference.h"
#include "tradeoff/ensemble.h"

namespace neurocloth {

// The method name of the paper's adaptive propagation (network integrator, Table 1).
inline constexpr const char* kAdaptiveMethod = "adaptive";
// The same propagation with the springs' damping taken implicitly
// (solver.damping "implicit", spring_damping.h). Swept only when named.
inline constexpr const char* kAdaptiveImplicitMethod = "adaptive_implicit";

// The adaptive propagation, either way: its rows vary "safety".
inline bool is_adaptive_method(const std::string& method) {
  return method == kAdaptiveMethod || method == kAdaptiveImplicitMethod;
}
// A method a trade may hold: an integrator's name or an adaptive method.
inline bool is_trade_method(const std::string& method) {
  return is_adaptive_method(method) || parse_integrator(method).has_value();
}
// "network, ..., projective, adaptive, adaptive_implicit" for error messages.
inline std::string trade_method_names() {
  return integrator_names() + ", " + kAdaptiveMethod + ", " + kAdaptiveImplicitMethod;
}

struct TradeRow {
  std::string method;     // an integrator's name, or an adaptive method
  std::string parameter;  // what the sweep varies: "dt" (fixed step) or "safety" (adaptive)
  double value = 0;       // its value
  double dt = 0;          // the fixed step, or the adaptive refresh interval t_delta, s
  // The projective integrator's local-global iterations per step (vbd's
  // sweeps): its accuracy knob besides dt, swept at each step. 0 for every other
  // method, and for a projective row of a file without the column (it then runs at the scene's own
  // solver.iterations, as it was measured).
  int iterations = 0;
  // The implicit step's conjugate-gradient tolerance (relative residual): its
  // accuracy knob besides dt, swept at each step. 0 for every other method, and
  // for an implicit_euler row of a file without the column (it then runs at the
  // scene's own solver.linear_tolerance, as it was measured).
  double linear_tolerance = 0;
  long steps = 0;
  // Relative to the cloth's size (positions) and to the energy scale (run_error.h);
  // NaN when the run did not finish (nothing to compare).
  double position_error_max = 0;
  double position_error_rms = 0;
  double energy_error = 0;
  // The distance to the ensemble in every metric (the median over its
  // members, cloth_metrics.h); NaN when the trade has no ensemble (a file
  // measured before it) or the run did not finish.
  MetricValues ensemble = unmeasured_metrics();
  double wall_per_simulated_second = 0;
  long force_evaluations = 0;
  long rejected_steps = 0;
  std::string status = "ok";  // "ok", "diverged", or "stopped" (ran out of step budget)

  bool ok() const { return status == "ok"; }
};

struct TradeTable {
  std::string scene;       // the scene's name
  std::string scene_file;  // as given to the command
  double seconds = 0;      // simulated per run
  int samples = 0;         // compared at this many evenly spaced times
  // The grid the cloth was measured on (0: not a grid scene, or a file that does
  // not say): a trade holds for that resolution only (sized_trade.h).
  int grid_rows = 0, grid_cols = 0;
  double cloth_size = 0;    // m
  double energy_scale = 0;  // J
  ReferenceReport reference;
  double wall_seconds = 0;  // the whole measurement
  // The scene's own spread (ensemble.h): absent in a trade measured without one.
  std::optional<EnsembleFloor> floor;
  // Why each method's sweep stopped ("network: levels"), in sweep order.
  std::vector<std::string> sweep_stops;
  std::vector<TradeRow> rows;
};

// A row's error in `metric`: its distance to the ensemble, or, in a trade
// without one, its max node error against the converged reference for
// node_max (NaN for the other metrics: not measured).
double row_error(const TradeRow& row, Metric metric);
// Whether `trade` measured `metric` (node_max always; the others with an ensemble).
bool has_metric(const TradeTable& trade, Metric metric);

// The solver settings a row stands for, on top of the scene's own (`base`): the
// one place a row becomes settings (`simulate --accuracy`, the viewer's slider).
// Throws std::invalid_argument for a method that is neither an integrator nor
// adaptive, iterations on a method that does not iterate, or a linear tolerance
// on one that solves no linear system.
SolverSettings settings_for(const TradeRow& row, SolverSettings base);
// The line a row belongs to on the chart: its method, "projective 4 it." or
// "implicit_euler tol 1e-6".
std::string line_name(const TradeRow& row);
// "rk4, dt 0.000488 s", "projective 4 it., dt 0.0156 s",
// "implicit_euler tol 1e-6, dt 0.0039 s" or "adaptive, safety 0.25 (t_delta 0.04 s)".
std::string describe_setting(const TradeRow& row);

}  // namespace neurocloth
