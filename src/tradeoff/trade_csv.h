#pragma once
// The trade as CSV: a few "# key: value" lines saying what was measured and how
// well the reference converged, one header line, one line per setting. Settings
// (value, dt) are written with 17 digits so a picked setting is exactly the one
// measured; measurements with 6. docs/tradeoff.md lists the columns.
#include <cstddef>
#include <string>

#include "tradeoff/trade_table.h"

namespace neurocloth {

// The columns, in order; the optional ones (below) may be absent.
inline constexpr const char* kTradeColumns[] = {"method",
                                                "parameter",
                                                "value",
                                                "dt",
                                                "iterations",
                                                "linear_tolerance",
                                                "steps",
                                                "position_error_max",
                                                "position_error_rms",
                                                "energy_error",
                                                "wall_per_simulated_second",
                                                "force_evaluations",
                                                "rejected_steps",
                                                "status",
                                                "ensemble_node_max",
                                                "ensemble_node_rms",
                                                "ensemble_surface_mean",
                                                "ensemble_surface_max",
                                                "ensemble_drape",
                                                "ensemble_stretch",
                                                "ensemble_energy"};
// Where the ensemble's columns start: one per metric, in kAllMetrics' order.
inline constexpr std::size_t kFirstEnsembleColumn = 14;

// Files written before projective's iterations, the implicit step's
// tolerance or the ensemble lack these; their rows then read as 0 (the scene's
// own setting) or NaN (not measured).
inline constexpr const char* kOptionalTradeColumns[] = {
    "iterations",        "linear_tolerance",      "ensemble_node_max",
    "ensemble_node_rms", "ensemble_surface_mean", "ensemble_surface_max",
    "ensemble_drape",    "ensemble_stretch",      "ensemble_energy"};

// The "# key: value" lines that describe the measurement, each at most once
// (sweep_stopped_by, one per stopped sweep, may repeat).
inline constexpr const char* kTradeMetadataKeys[] = {"scene",
                                                     "scene_file",
                                                     "seconds",
                                                     "samples",
                                                     "grid",
                                                     "cloth_size_m",
                                                     "energy_scale_j",
                                                     "reference_dt",
                                                     "reference_change",
                                                     "reference_rms_change",
                                                     "reference_change_by_sample",
                                                     "reference_target",
                                                     "reference_met",
                                                     "reference_stopped_by",
                                                     "reference_runs",
                                                     "reference_wall_seconds",
                                                     "wall_seconds",
                                                     "ensemble",
                                                     "ensemble_shift_m",
                                                     "ensemble_seed",
                                                     "ensemble_dt"};
// With an ensemble, per metric M: "# floor_M: MEDIAN P90" over the pairs of
// references and the run, and "# floor_M_median_by_sample: ..." and
// "# floor_M_p90_by_sample: ..." at each compared time ("none": not measured).

std::string trade_csv(const TradeTable& table);

// Reads what trade_csv wrote. Throws InputError naming `path`, the line and
// column, and the field (a column or a "# key") for anything wrong; never
// returns a half-read table.
TradeTable parse_trade_csv(const std::string& text, const std::string& path);
TradeTable read_trade_csv(const std::string& path);
// The same, for a cloth of n x n nodes: also throws InputError naming `path` and
// the field '# grid' when the file does not say it was measured at n x n (a
// trade at 32 x 32 says nothing of the error at 128 x 128).
TradeTable read_sized_trade(const std::string& path, int n);

}  // namespace neurocloth
