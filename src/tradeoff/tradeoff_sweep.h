#pragma once
// Measures the trade on one scene: the converged RK4 reference first, then
// every integrator over a sweep of fixed steps and the paper's adaptive
// propagation over a sweep of its safety factor, each compared with the
// reference at the same sample times (docs/tradeoff.md says why these knobs
// and these stopping rules).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "tradeoff/trade_table.h"

namespace neurocloth {

struct TradeoffPlan {
  double seconds = 2;  // simulated per run
  int samples = 8;     // compared at seconds * j / samples, j = 1..samples
  ReferencePlan reference;
  // Each method's sweep halves its step (or safety) from its largest useful
  // value and stops at the first of: `max_levels` settings; an error at or
  // below `error_floor` (a finer step cannot be the cheapest for any budget at
  // or above it); an error within twice the reference's own change, once it has
  // `min_levels` settings (finer ones could not be told from the reference); or
  // a next run predicted to overrun `method_budget_seconds` of run cost for the
  // method (each run's cost on run_clock, sampled_run.h).
  int max_levels = 7;
  int min_levels = 3;
  double error_floor = 1e-4;
  double method_budget_seconds = 8;
  // Projective's second knob: its sweep runs each of these iterations counts at
  // every step it tries (docs/tradeoff.md says why these). Each in [1, 1000].
  std::vector<int> projective_iterations = {1, 2, 4, 10, 30};
  // vbd's sweeps per step, likewise: more than projective's, since each carries
  // a change a few nodes across the cloth, not across all of it.
  std::vector<int> vbd_iterations = {4, 10, 30, 100};
  // The implicit step's second knob, likewise: its conjugate-gradient tolerance
  // (relative residual; docs/tradeoff.md says why these). Each in [1e-14, 0.01].
  std::vector<double> implicit_tolerances = {1e-10, 1e-6, 1e-3};
  // When not empty, every fixed-step method (projective and implicit_euler too,
  // at each setting of their second knob) runs exactly these steps instead of its halving sweep,
  // with no stopping rule: to measure the settings something else will run (the
  // window's real-time pick, realtime_pick.h). Each must divide the sample
  // interval seconds / samples into whole steps. RK4 and adaptive are unchanged.
  std::vector<double> steps;
  // The methods to sweep (integrator names and/or "adaptive"); empty: all of them.
  // RK4's line always comes from the reference's own runs.
  std::vector<std::string> methods;
  // Method lines measured at once, each on a thread of its own: 0 is one per
  // core; 1 measures them one after another. With more than one at work, every
  // line's runs step on one thread (the scene's solver.threads is for the
  // reference then, and for a lone line). The table does not depend on it but
  // for its cost figures. In [0, kMaxTradeoffWorkers].
  int workers = 0;
  // The scene's own spread (ensemble.h): with members, every finished row is
  // also measured in every metric against each member, and the table gets the
  // floor. The members run RK4 at the coarsest of the reference's steps that
  // lies within kMemberTolerance of its finest run (its finest when none does).
  EnsemblePlan ensemble;
};

// How near the finest reference run a member's RK4 step must land (of the
// cloth's size, at every compared time): far below any spread a shift of a
// nanometre makes, so the members differ by their shifts, not their steps.
inline constexpr double kMemberTolerance = 1e-6;

inline constexpr int kMaxTradeoffWorkers = 64;

// The workers a plan's `workers` gives for `lines` method lines on this
// machine: at least 1, at most `lines`.
int tradeoff_workers(int workers, std::size_t lines);

// Throws std::invalid_argument for a plan it cannot run (seconds <= 0, samples < 1,
// an ensemble out of range,
// an unknown method, projective with no iterations count or one out of range,
// implicit_euler with no tolerance or one out of range, a step out of range or
// not dividing the sample interval, workers out of range), std::runtime_error
// when even the reference diverges. `log` is called on the calling thread
// only: live while the lines run one at a time, else each line's lines as one
// block when it and every line before it are done, in method order.
TradeTable measure_tradeoff(const Scene& scene, const std::string& scene_file,
                            const TradeoffPlan& plan,
                            const std::function<void(const std::string&)>& log = {});

// The sweep's largest fixed step for `kind` on `scene`: the largest
// interval / 2^k at or below twice the explicit stability bound by Gershgorin's
// discs (so the first setting may sit just past the true limit), or
// interval / 4 for the implicit step.
double first_step(const Scene& scene, IntegratorKind kind, double interval);

// Why `dt` cannot be one of a plan's steps for sample interval `interval`
// (out of the step limits, or not a whole number of steps per interval), or
// empty when it can.
std::string step_refusal(double dt, double interval);

}  // namespace neurocloth
