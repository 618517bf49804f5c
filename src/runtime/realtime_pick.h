#pragma once
// What the window runs when the scene's own solver cannot keep a resized cloth
// in real time. A finer grid of the same cloth needs a smaller stable step on
// more springs: the table drape at 128 x 128 runs about 0.01x real time with
// its adaptive network step. The window then takes the large-step `projective`
// integrator at one step per frame, with as many local-global iterations (its
// accuracy knob) as the machine can afford, and says so; the Solver panel
// offers the scene's own solver back.
#include <functional>
#include <optional>
#include <string>

#include "core/scene/scene.h"
#include "tradeoff/trade_table.h"

namespace neurocloth {

// What is measured of the picked settings' error at a resized cloth's size: a
// trade measured at the scene's own size says nothing of a finer cloth's.
struct SizedTrade {
  int size = 0;                     // N: the cloth is N x N
  std::string path;                 // where the trade at this size lives (sized_trade_path)
  std::optional<TradeTable> table;  // read from it, its size checked; none: not measured
  std::string problem;              // why a file that is there could not be used
  std::string measure;              // the command that measures it, at kRealtimeStep
  // The same command around its step, for a pick that halved it:
  // measure_before + "1/120" + measure_after.
  std::string measure_before, measure_after;
};

// The trade of `scene_path` resized to n x n, read from `path` when the file
// is there. Never throws: a broken file, or one measured at another size, is
// reported in `problem` (the window opens without the quote).
SizedTrade find_sized_trade(const std::string& scene_path, int n, const std::string& path);
SizedTrade find_sized_trade(const std::string& scene_path, int n);  // at sized_trade_path

struct RealtimePick {
  bool switched = false;  // false: the scene's own solver keeps up (or nothing was asked)
  SolverSettings own;     // the scene's
  SolverSettings picked;  // what runs (own when not switched)
  double own_cost = 0;    // wall seconds per simulated second, measured on this machine
  double picked_cost = 0;
  // The picked setting's row of the sized trade (projective, kRealtimeStep, its
  // iterations), when it was measured at this size; and the file it is from.
  std::optional<TradeRow> measured;
  std::string measured_in;
  std::string note;  // for the Solver panel and the terminal
};

// Wall seconds per simulated second of `scene` under its solver (a probe).
using CostProbe = std::function<double(const Scene&)>;
// Whether `scene` under its solver runs through its first kSoundSeconds
// without diverging (runs_sound; a probe so the pick's logic is testable).
using SoundProbe = std::function<bool(const Scene&)>;

// The step a picked setting takes: one per frame of a 60 Hz display.
inline constexpr double kRealtimeStep = 1.0 / 60.0;
// A setting keeps up when it costs at most this share of real time: the rest
// is for the window and for the cloth's harder moments than the probe's.
inline constexpr double kRealtimeBudget = 0.7;
// What a picked setting must run through without diverging: the sized trades'
// window (docs/tradeoff.md), the fall and the drape over the table's edge.
inline constexpr double kSoundSeconds = 1.0;
// Halvings of kRealtimeStep the pick tries when a setting diverges there
// (1/120, 1/240, 1/480 s).
inline constexpr int kMaxStepHalvings = 3;

// Keeps the scene's solver when `cost` says it keeps up; else the projective
// step at kRealtimeStep (or a halving of it, below) with the most iterations
// (1..kDefaultProjectiveIterations) whose cost, interpolated linearly from probes at 1 and 4
// iterations, fits the budget; else 1 iteration, saying that even it does not keep up. When `trade`
// holds measured errors for counts that fit, the fewest iterations whose error
// is within the reference's resolution of the least among them is taken
// instead (a quoted error beats an unmeasured guess, and fewer iterations
// leave the renderer more of the machine), and the note quotes it; otherwise
// the note says the error is not measured and how to (nothing, when `trade`
// names no file: nobody looked).
//
// With `sound`, the setting must also run through the cloth's first
// kSoundSeconds: a large step on a fine cloth can land it on a table by a
// step's fall at once and stretch it over the edge into a divergence (the
// 256 x 256 drape at 1/60 s). Then the step is halved (up to
// kMaxStepHalvings times, the iterations chosen again for its doubled cost)
// until one runs through, and the note says so.
RealtimePick pick_for_real_time(const Scene& scene, const CostProbe& cost,
                                const SizedTrade& trade = {}, const SoundProbe& sound = {});

// Runs a copy of `scene` through its first `seconds`, checked after every
// frame (kRealtimeStep, or its step when longer) as the window checks, and its
// end as `simulate` checks a result (Simulation::check_result): false when it
// diverged. Deterministic (the same answer on any machine), unlike measure_cost.
bool runs_sound(const Scene& scene, double seconds);

// Runs a copy of `scene` for about `wall_seconds` (at most `max_sim_seconds`
// simulated) after one untimed step (a factorisation, a first contact) and
// returns wall seconds per simulated second. Wall-clock: for the window's
// start, never for a test.
double measure_cost(const Scene& scene, double wall_seconds, double max_sim_seconds = 0.5);

}  // namespace neurocloth
