#include "runtime/realtime_pick.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "tradeoff/accuracy_choice.h"
#include "tradeoff/trade_csv.h"

namespace neurocloth {

namespace {

Scene with_solver(const Scene& scene, const SolverSettings& s) {
  Scene copy = scene;
  copy.solver = s;
  return copy;
}

SolverSettings projective(const SolverSettings& own, int iterations, int halvings = 0) {
  SolverSettings s = own;
  s.integrator = IntegratorKind::projective;
  s.adaptive = false;
  s.dt = kRealtimeStep / (1 << halvings);
  s.iterations = iterations;
  return s;
}

// "1/60", "1/120": the step kRealtimeStep halved `halvings` times.
std::string step_name(int halvings) {
  return "1/" + std::to_string(60 << halvings);
}

std::string format(const char* pattern, double value) {
  char line[128];
  std::snprintf(line, sizeof line, pattern, value);
  return line;
}

// The trade's row for projective at `dt` and `iterations` that finished its
// run, if any.
const TradeRow* measured_row(const SizedTrade& trade, int iterations, double dt) {
  if (!trade.table) return nullptr;
  for (const TradeRow& row : trade.table->rows)
    if (row.method == to_string(IntegratorKind::projective) && row.parameter == "dt" &&
        std::abs(row.dt - dt) <= 1e-9 * dt && row.iterations == iterations && row.ok())
      return &row;
  return nullptr;
}

// Of the counts up to `most` (all fit the budget), the measured one of least
// error; `most` when none is measured. Errors within the reference's
// resolution of the least cannot be told apart: the fewest iterations among
// those win then, leaving the window's renderer the most of the machine
// (llvmpipe draws on the same cores).
int least_measured_error(const SizedTrade& trade, int most, double dt) {
  if (!trade.table) return most;
  const Metric metric = default_metric(*trade.table);
  const TradeRow* least = nullptr;
  for (int it = 1; it <= most; ++it)
    if (const TradeRow* row = measured_row(trade, it, dt);
        row && (!least || row_error(*row, metric) < row_error(*least, metric)))
      least = row;
  if (!least) return most;
  // Below the scene's own spread (or, without an ensemble, within the
  // reference's resolution of the least) errors cannot be told apart.
  const double same =
      trade.table->floor
          ? std::max(row_error(*least, metric), trade.table->floor->p90[slot(metric)])
          : row_error(*least, metric) + reference_resolution(*trade.table);
  for (int it = 1; it <= most; ++it)
    if (const TradeRow* row = measured_row(trade, it, dt); row && row_error(*row, metric) <= same)
      return it;
  return least->iterations;
}

// What the note says of the picked setting's error at this size (its step
// kRealtimeStep halved `halvings` times).
std::string error_sentence(const RealtimePick& pick, const SizedTrade& trade, int size,
                           int halvings) {
  if (trade.path.empty()) return "";  // nobody looked for one
  const std::string grid = std::to_string(size) + " x " + std::to_string(size);
  if (pick.measured && trade.table->floor) {
    const TradeRow& row = *pick.measured;
    const Metric metric = default_metric(*trade.table);
    const double error = row_error(row, metric), spread = trade.table->floor->p90[slot(metric)];
    char s[512];
    std::snprintf(s, sizeof s,
                  " Measured at %s: projective %d it., dt %s s: error %.2g%% (%s; spread %.2g%%) "
                  "over its first %g s, %s the scene's own spread (%d references shifted %g mm), "
                  "in %s.",
                  grid.c_str(), row.iterations, step_name(halvings).c_str(), 100 * error,
                  to_string(metric), 100 * spread, trade.table->seconds,
                  error <= spread ? "within" : "outside", trade.table->floor->members,
                  1000 * trade.table->floor->shift, pick.measured_in.c_str());
    return s;
  }
  if (pick.measured) {
    const TradeRow& row = *pick.measured;
    char s[512];
    std::snprintf(s, sizeof s,
                  " Measured at %s: projective %d it., dt %s s: max position error %.2g%% of "
                  "the cloth's size over its first %g s (rms %.2g%%; the reference is good to "
                  "%.2g%%), in %s.",
                  grid.c_str(), row.iterations, step_name(halvings).c_str(),
                  100 * row.position_error_max, trade.table->seconds, 100 * row.position_error_rms,
                  100 * reference_resolution(*trade.table), pick.measured_in.c_str());
    return s;
  }
  std::string says = " Its error at " + grid + " is not measured";
  if (!trade.problem.empty()) says += " (" + trade.problem + ")";
  if (!trade.measure.empty())
    says += "; to measure it: " +
            (halvings == 0 ? trade.measure
                           : trade.measure_before + step_name(halvings) + trade.measure_after);
  return says + ".";
}

}  // namespace

SizedTrade find_sized_trade(const std::string& scene_path, int n, const std::string& path) {
  SizedTrade trade;
  trade.size = n;
  trade.path = path;
  std::string iterations;
  for (int it = 1; it <= kDefaultProjectiveIterations; ++it)
    iterations += (it > 1 ? "," : "") + std::to_string(it);
  const std::string out = path.size() > 4 && path.compare(path.size() - 4, 4, ".csv") == 0
                              ? path.substr(0, path.size() - 4)
                              : path;
  // The window's settings exactly, against a reference the user can afford
  // (docs/tradeoff.md, "Sized trades": what it cost at 64 and 128).
  trade.measure_before = "neurocloth-cli tradeoff " + scene_path + " --size " + std::to_string(n) +
                         " --seconds 1 --samples 4 --methods projective --dt ";
  trade.measure_after =
      " --projective-iterations " + iterations + " --reference-budget 1200 --out " + out;
  trade.measure = trade.measure_before + step_name(0) + trade.measure_after;
  std::error_code missing;
  if (!std::filesystem::exists(path, missing)) return trade;
  try {
    trade.table = read_sized_trade(path, n);
  } catch (const std::runtime_error& e) {  // InputError: broken, or measured at another size
    trade.problem = e.what();
  }
  return trade;
}

SizedTrade find_sized_trade(const std::string& scene_path, int n) {
  return find_sized_trade(scene_path, n, sized_trade_path(scene_path, n));
}

RealtimePick pick_for_real_time(const Scene& scene, const CostProbe& cost, const SizedTrade& trade,
                                const SoundProbe& sound) {
  RealtimePick pick;
  pick.own = pick.picked = scene.solver;
  pick.own_cost = pick.picked_cost = cost(scene);
  if (pick.own_cost <= kRealtimeBudget) return pick;

  // The projective step's cost grows linearly with its iterations (one local
  // step and one prefactored solve each) on top of what a step costs anyway,
  // and doubles with each halving of the step.
  const double one = cost(with_solver(scene, projective(scene.solver, 1)));
  const double four = cost(with_solver(scene, projective(scene.solver, 4)));
  const double per_iteration = std::max(0.0, (four - one) / 3);
  auto fitting = [&](int halvings) {
    const double scale = double(1 << halvings);
    for (int it = kDefaultProjectiveIterations; it > 1; --it)
      if (scale * (one + (it - 1) * per_iteration) <= kRealtimeBudget) return it;
    return 1;
  };
  int halvings = 0, iterations = least_measured_error(trade, fitting(0), kRealtimeStep);
  std::string unsound;  // the steps that diverged, "1/60, 1/120"
  bool ran_through = true;
  if (sound) {
    while (!(ran_through =
                 sound(with_solver(scene, projective(scene.solver, iterations, halvings))))) {
      unsound += (unsound.empty() ? "" : ", ") + step_name(halvings);
      if (halvings == kMaxStepHalvings) break;
      ++halvings;
      iterations = least_measured_error(trade, fitting(halvings), kRealtimeStep / (1 << halvings));
    }
  }
  const double dt = kRealtimeStep / (1 << halvings);
  if (const TradeRow* row = measured_row(trade, iterations, dt)) {
    pick.measured = *row;
    pick.measured_in = trade.path;
  }
  pick.switched = true;
  pick.picked = projective(scene.solver, iterations, halvings);
  pick.picked_cost = double(1 << halvings) * (one + (iterations - 1) * per_iteration);
  std::string note = "Running projective, " + std::to_string(iterations) +
                     (iterations == 1 ? " iteration" : " iterations") + ", dt " +
                     step_name(halvings) + " s, to keep real time: the scene's " +
                     to_string(scene.solver.integrator) +
                     format(" step runs %.2gx real time at this size", 1 / pick.own_cost);
  if (pick.picked_cost > 1)
    note += format("; even this runs only %.2gx", 1 / pick.picked_cost);
  else if (pick.picked_cost > kRealtimeBudget)
    note += format("; this runs %.2gx, with little to spare", 1 / pick.picked_cost);
  note += ".";
  if (!unsound.empty()) {
    note += " At dt " + unsound + " s it diverged within the cloth's first " +
            format("%g s", kSoundSeconds) +
            " (a large step lands a fine cloth a whole step's fall at once and stretches it over "
            "an edge)" +
            (ran_through ? "." : "; no step tried ran through, so expect it to stop.");
  }
  pick.note =
      note + error_sentence(pick, trade, scene.grid ? scene.grid->rows : trade.size, halvings);
  return pick;
}

bool runs_sound(const Scene& scene, double seconds) {
  // On as many threads as the machine spares: the bits, and so the answer,
  // do not depend on them (step_threads.h).
  Scene copy = scene;
  copy.solver.threads = batch_step_threads(scene.topology.rest_positions.size());
  Simulation sim = copy.make_simulation();
  // Frame by frame, checked after each as the window's thread checks each
  // frame it publishes: a divergence stops the probe where the window would
  // stop (and early: at 256² and 1/60 s, at 0.22 s of the second).
  const double frame = std::max(scene.solver.dt, kRealtimeStep);
  for (long k = 1; sim.status() == RunStatus::ok && sim.time() < seconds; ++k) {
    sim.advance(std::min(seconds, double(k) * frame) - sim.time());
    sim.check_now();
  }
  return sim.check_result() == RunStatus::ok;
}

double measure_cost(const Scene& scene, double wall_seconds, double max_sim_seconds) {
  using Clock = std::chrono::steady_clock;
  Simulation sim = scene.make_simulation();
  // Fixed steps advance a whole step at a time (a part step would be a one-off
  // of another length); an adaptive run in short pieces, so that the probe
  // stops near its wall time even when a piece is slow.
  const double frame =
      scene.solver.adaptive ? std::min(scene.solver.dt, 1.0 / 240) : scene.solver.dt;
  sim.advance(frame);  // untimed: the first factorisation, the first contact
  const double t0 = sim.time();
  const Clock::time_point start = Clock::now();
  double wall = 0;
  while (sim.status() == RunStatus::ok && sim.time() - t0 < max_sim_seconds) {
    sim.advance(frame);
    wall = std::chrono::duration<double>(Clock::now() - start).count();
    if (wall >= wall_seconds) break;
  }
  const double simulated = sim.time() - t0;
  if (!(simulated > 0)) return std::numeric_limits<double>::infinity();
  return wall / simulated;
}

}  // namespace neurocloth
