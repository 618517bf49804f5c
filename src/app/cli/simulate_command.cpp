#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>

#include "app/cli/commands.h"
#include "app/cli/long_run.h"
#include "app/cli/motion_outputs.h"
#include "app/cli/result_json.h"
#include "core/io/input_error.h"
#include "core/scene/scene.h"
#include "tradeoff/accuracy_choice.h"
#include "tradeoff/trade_csv.h"
#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth {
namespace {

// What --accuracy picked, and from which trade: printed and put in RESULT.json.
struct AccuracyPick {
  double requested = 0;
  std::string trade;  // the CSV it came from, or "measured now"
  double trade_seconds = 0;
  TradeRow row;
  int iterations = 0;  // projective: the iterations per step it runs at (the row's or the scene's)
  double linear_tolerance = 0;  // implicit_euler: its CG tolerance (the row's or the scene's)
  AccuracyChoice choice;
};

// The trade to pick from: --trade, else the committed one, else measured now.
TradeTable find_trade(const SimulateOptions& o, const Scene& scene, std::string& source) {
  if (o.trade) {
    source = *o.trade;
    return o.size ? read_sized_trade(*o.trade, *o.size) : read_trade_csv(*o.trade);
  }
  // A trade holds at the resolution it was measured at: a resized cloth's is its own.
  const std::string committed =
      o.size ? sized_trade_path(o.scene, *o.size) : committed_trade_path(o.scene);
  if (std::filesystem::exists(committed)) {
    source = committed;
    return o.size ? read_sized_trade(committed, *o.size) : read_trade_csv(committed);
  }
  TradeoffOptions options;
  options.scene = o.scene;
  options.size = o.size;
  if (o.seconds > 0) options.seconds = o.seconds;
  const TradeoffPlan plan = tradeoff_plan(options);
  std::printf(
      "%s: no measured trade (looked for %s): measuring one over %g s first; keep it with\n"
      "  neurocloth-cli tradeoff %s --seconds %g --out REPORT, then --trade REPORT.csv\n",
      scene.name.c_str(), committed.c_str(), plan.seconds, o.scene.c_str(), plan.seconds);
  std::fflush(stdout);
  source = "measured now";
  return measure_trade(scene, o.scene, plan);
}

AccuracyPick pick_for_accuracy(const SimulateOptions& o, Scene& scene) {
  AccuracyPick pick;
  pick.requested = *o.accuracy;
  if (!(pick.requested > 0) || !std::isfinite(pick.requested))
    throw InputError("command line", "--accuracy",
                     "must be a finite number > 0 (a fraction of the cloth's size: 0.01 is 1%)");
  const TradeTable trade = find_trade(o, scene, pick.trade);
  if (trade.scene != scene.name)
    throw InputError(pick.trade, "# scene",
                     "measured for scene '" + trade.scene + "', not for '" + scene.name + "'");
  std::optional<Metric> metric;
  if (o.metric) metric = metric_option(*o.metric, "--metric");
  const AccuracyChoice c = choose_for_accuracy(trade, pick.trade, pick.requested, scene.solver,
                                               "--accuracy", metric, "--metric");
  pick.choice = c;
  scene.solver = c.settings;
  // The trade is measured in double (tradeoff_sweep.cpp): its pick runs so.
  const bool was_float = scene.solver.precision != SpringPrecision::float64;
  scene.solver.precision = SpringPrecision::float64;
  pick.row = c.row;
  if (iterates_per_step(c.settings.integrator)) pick.iterations = c.settings.iterations;
  if (c.settings.integrator == IntegratorKind::implicit_euler)
    pick.linear_tolerance = c.settings.linear_tolerance;
  pick.trade_seconds = trade.seconds;
  if (!c.floor_note.empty()) std::printf("%s\n", c.floor_note.c_str());
  if (std::isfinite(c.floor))
    std::printf(
        "accuracy %g (%s): picked %s from %s (measured over %g s: %s %.3g to the ensemble, "
        "%s the scene's spread %.3g; %.3g s per simulated s)\n",
        pick.requested, to_string(c.metric), describe_setting(c.row).c_str(), pick.trade.c_str(),
        trade.seconds, to_string(c.metric), c.error, c.within_floor() ? "within" : "outside",
        c.floor, c.row.wall_per_simulated_second);
  else
    std::printf(
        "accuracy %g: picked %s from %s (measured over %g s: max error %.3g, RMS %.3g, %.3g s "
        "per simulated s)\n",
        pick.requested, describe_setting(c.row).c_str(), pick.trade.c_str(), trade.seconds,
        c.row.position_error_max, c.row.position_error_rms, c.row.wall_per_simulated_second);
  if (was_float)
    std::printf(
        "  note: the scene's solver.precision is float; the pick runs in double, as it "
        "was measured\n");
  if (o.seconds > trade.seconds)
    std::printf("  note: this run is longer than the measured %g s; errors may grow beyond it\n",
                trade.seconds);
  return pick;
}

nlohmann::json accuracy_json(const AccuracyPick& p) {
  nlohmann::json j = {{"requested", p.requested},
                      {"trade", p.trade},
                      {"trade_seconds", p.trade_seconds},
                      {"method", p.row.method},
                      {"parameter", p.row.parameter},
                      {"value", p.row.value},
                      {"dt", p.row.dt},
                      {"measured_position_error_max", p.row.position_error_max},
                      {"measured_position_error_rms", p.row.position_error_rms},
                      {"measured_wall_per_simulated_second", p.row.wall_per_simulated_second}};
  const AccuracyChoice& c = p.choice;
  j["metric"] = to_string(c.metric);
  j["measured_error"] = c.error;
  if (std::isfinite(c.floor)) {
    j["floor"] = c.floor;
    j["picked_against"] = c.target;
    j["within_floor"] = c.within_floor();
  }
  if (p.iterations > 0) j["iterations"] = p.iterations;
  if (p.linear_tolerance > 0) j["linear_tolerance"] = p.linear_tolerance;
  return j;
}

}  // namespace

SpringPrecision precision_option(const std::string& name) {
  const auto precision = parse_precision(name);
  if (!precision)
    throw InputError("command line", "--precision",
                     "unknown precision '" + name + "' (expected one of: " + kPrecisionNames + ")");
  return *precision;
}

int run_simulate(const SimulateOptions& o) {
  if (!(o.seconds >= 0) || !std::isfinite(o.seconds))
    throw InputError("command line", "--seconds", "must be a finite number >= 0");
  Scene scene = sized_scene(load_scene(o.scene), o.scene, o.size);
  // What the cloth cannot represent of a measured material (a grid without
  // shear springs, a mesh's shear fixed by its triangles).
  for (const std::string& note : scene.material_notes)
    std::printf("  note: %s\n", note.c_str());
  check_output_path("--out", o.out, input_files(scene));
  std::optional<AccuracyPick> accuracy;
  if (o.accuracy) accuracy = pick_for_accuracy(o, scene);
  if (o.integrator) {
    const auto kind = parse_integrator(*o.integrator);
    if (!kind)
      throw InputError("command line", "--integrator",
                       "unknown integrator '" + *o.integrator +
                           "' (expected one of: " + integrator_names() + ")");
    scene.solver.integrator = *kind;
    // It takes fixed steps: asked for by name on an adaptive scene, it gets them.
    if (iterates_per_step(*kind)) scene.solver.adaptive = false;
  }
  if (o.dt) {
    if (!(*o.dt > 0) || !std::isfinite(*o.dt))
      throw InputError("command line", "--dt", "must be a finite number > 0");
    scene.solver.dt = *o.dt;
  }
  if (o.iterations) {
    if (!limits::kIterations.contains(*o.iterations))
      throw InputError("command line", "--iterations",
                       "must be in [1, 1000] (" + std::string(limits::kIterations.meaning) +
                           "), got " + std::to_string(*o.iterations));
    scene.solver.iterations = *o.iterations;
  }
  if (o.adaptive) scene.solver.adaptive = true;
  if (o.fixed_step) scene.solver.adaptive = false;
  if (o.threads && (*o.threads < 1 || *o.threads > kMaxStepThreads))
    throw InputError("command line", "--threads",
                     "must be in [1, " + std::to_string(kMaxStepThreads) + "]");
  scene.solver.threads =
      o.threads ? *o.threads : batch_step_threads(scene.topology.rest_positions.size());
  if (o.precision) scene.solver.precision = precision_option(*o.precision);
  if (o.damping && !parse_damping(*o.damping, scene.solver.damping))
    throw InputError(
        "command line", "--damping",
        "unknown damping '" + *o.damping + "' (expected one of: " + kDampingNames + ")");
  if (o.step_bound && !parse_step_bound(*o.step_bound, scene.solver.step_bound))
    throw InputError(
        "command line", "--step-bound",
        "unknown step bound '" + *o.step_bound + "' (expected one of: " + kStepBoundNames + ")");
  if (o.safety) {
    if (!(*o.safety > 0 && *o.safety <= 1))
      throw InputError("command line", "--safety", "must be in (0, 1]");
    scene.solver.adaptive_settings.safety = *o.safety;
  }
  if (scene.solver.damping == DampingMode::implicit_springwise &&
      scene.solver.integrator != IntegratorKind::network)
    throw InputError("command line", o.damping ? "--damping" : "--integrator",
                     std::string("solver.damping \"implicit\" is for the network integrator, "
                                 "not ") +
                         to_string(scene.solver.integrator));
  const std::string conflict = precision_conflict(scene.solver.integrator, scene.solver.precision);
  if (!conflict.empty())
    throw InputError("command line", o.precision ? "--precision" : "--integrator",
                     "solver.precision " + conflict);

  if (!(o.progress >= 0) || !std::isfinite(o.progress))
    throw InputError("command line", "--progress", "must be a finite number >= 0 (wall seconds)");

  if (o.record_fps && !o.record && !o.export_pc2)
    throw InputError("command line", "--record-fps", "needs --record FILE or --export-pc2 FILE");
  // Opened before the run: a bad option or an unwritable path costs no run.
  std::optional<MotionOutputs> motion;
  if (o.record || o.export_pc2) motion.emplace(o, scene);

  Simulation sim = scene.make_simulation();
  // A batch run takes the fixed step it asked for (docs/stability.md); one
  // above the stable step is said before the run, and a divergence then names it.
  if (!scene.solver.adaptive && sim.step_cap() < scene.solver.dt)
    std::printf(
        "  note: dt = %g s is above the stable step of %s on this cloth (%.3g s): it may "
        "diverge (--adaptive, or a dt below that, does not)\n",
        scene.solver.dt, to_string(scene.solver.integrator), sim.step_cap());
  LongRunOutcome run;
  if (motion) {
    motion->frame(sim.time(), sim.state());  // frame 0: the initial state
    run =
        run_long_frames(sim, o.seconds, motion->fps(),
                        [&](double t, const ClothState& s) { motion->frame(t, s); }, {o.progress});
  } else {
    run = run_long(sim, o.seconds, {o.progress});
  }
  sim.check_result();  // the result is checked in full, whatever the cadence
  const double wall = run.wall_seconds;
  nlohmann::json result = simulation_result(sim, scene.topology.numbering, o.scene, wall);
  if (accuracy) result["accuracy"] = accuracy_json(*accuracy);
  result["seconds_asked"] = o.seconds;
  result["interrupted"] = run.interrupted;
  // A run the step budget stopped is healthy but short of what was asked:
  // the result says so, and so do the message and the exit code.
  const bool stopped_early =
      sim.status() == RunStatus::ok && sim.budget_exhausted() && !run.interrupted;
  result["step_budget_exhausted"] = stopped_early;
  const std::vector<FabricTestReading> readings = fabric_test_readings(scene, sim.state());
  for (const FabricTestReading& r : readings)
    result[r.key] = r.json;
  std::vector<std::string> motion_lines;
  if (motion) {
    motion->keep_until(sim);
    result["motion"] = motion->result_json();
    motion_lines = motion->finish(sim);
  }
  write_json_atomically(o.out, result);

  const Energy e = sim.energy();
  std::printf("%s: %s at t = %.4g s after %ld steps (%ld rejected), %s%s, %.3g s wall\n",
              scene.name.c_str(), to_string(sim.status()), sim.time(), sim.steps(),
              sim.rejected_steps(), to_string(scene.solver.integrator),
              scene.solver.adaptive ? " adaptive" : "", wall);
  std::printf("  %zu nodes, %zu springs; energy: kinetic %.6g J, potential %.6g J, total %.6g J\n",
              sim.network().node_count(), sim.network().spring_count(), e.kinetic, e.potential(),
              e.total());
  for (const ModuleReport& m : sim.module_reports())
    std::printf("  module %-14s %8.3g s in %ld calls (%.3g us each)\n", m.type.c_str(), m.seconds,
                m.calls, m.calls ? 1e6 * m.seconds / m.calls : 0.0);
  for (const FabricTestReading& r : readings)
    std::printf("  %s\n", r.line.c_str());
  if (sim.status() != RunStatus::ok)
    std::printf("  diverged: %s; kept the last good state (t = %.4g s)\n",
                sim.divergence_reason().c_str(), sim.time());
  if (stopped_early)
    std::printf(
        "  stopped early at t = %.4g s of %.4g s: the step budget (%ld trial steps per dt) ran "
        "out; the stable step here is %.3g s (docs/stability.md)\n",
        sim.time(), o.seconds, sim.settings().step_budget, sim.step_cap());
  if (run.interrupted)
    std::printf("  interrupted (Ctrl-C) at t = %.6g s of %.6g s; the state reached is written\n",
                sim.time(), o.seconds);
  for (const std::string& line : motion_lines)
    std::printf("  %s\n", line.c_str());
  std::printf("  wrote %s\n", o.out.c_str());
  if (sim.status() != RunStatus::ok) return kExitDiverged;
  if (run.interrupted) return kExitInterrupted;
  return stopped_early ? kExitStoppedEarly : kExitOk;
}

}  // namespace neurocloth
