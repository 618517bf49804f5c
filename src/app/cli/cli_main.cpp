// neurocloth-cli: batch access to the simulation core (simulate, relax, bench,
// material, tradeoff, fit, tune-rules) and headless snapshots (snapshot).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

#include "app/cli/commands.h"
#include "core/base/cpu_features.h"
#include "core/io/input_error.h"
#include "tradeoff/tradeoff_sweep.h"

int main(int argc, char** argv) {
  using namespace neurocloth;
  CLI::App app{"neurocloth-cli: the neuro-fuzzy cloth network from the command line"};
  app.require_subcommand(1);

  SimulateOptions sim;
  auto* simulate =
      app.add_subcommand("simulate", "Run a scene forward in time and write RESULT.json");
  simulate->add_option("scene", sim.scene, "Scene file (JSON)")->required();
  simulate->add_option("--seconds", sim.seconds, "Simulated seconds (0 writes the initial state)")
      ->required();
  simulate->add_option("--integrator", sim.integrator, "One of: " + integrator_names());
  simulate->add_option("--dt", sim.dt, "Time step (the refresh interval when adaptive), s");
  simulate->add_option("--iterations", sim.iterations,
                       "projective: local-global iterations per step; vbd: sweeps (default " +
                           std::to_string(kDefaultProjectiveIterations) + ")");
  auto* adaptive =
      simulate->add_flag("--adaptive", sim.adaptive, "Adaptive propagation (paper, Table 1)");
  auto* fixed = simulate->add_flag("--fixed-step", sim.fixed_step, "Fixed time step");
  adaptive->excludes(fixed);
  simulate->add_option("--out", sim.out, "Where to write RESULT.json")->required();
  simulate->add_option("--progress", sim.progress,
                       "Wall seconds between progress lines on stderr (default 2; 0: none). "
                       "Ctrl-C ends a run and writes the state reached");
  auto* accuracy = simulate->add_option(
      "--accuracy", sim.accuracy,
      "Pick the cheapest measured setting keeping the max position error within this fraction "
      "of the cloth's size (0.01 = 1%)");
  accuracy->excludes("--integrator")
      ->excludes("--dt")
      ->excludes("--iterations")
      ->excludes(adaptive)
      ->excludes(fixed);
  simulate
      ->add_option("--trade", sim.trade,
                   "The measured trade (tradeoff's CSV) --accuracy picks from; default "
                   "assets/tradeoff/<scene>.csv, else measured first")
      ->needs(accuracy);
  simulate
      ->add_option("--metric", sim.metric,
                   "The error --accuracy is in: " + metric_names() +
                       " (default: " + std::string(to_string(kDefaultMetric)) +
                       " where the trade measured it, else node_max)")
      ->needs(accuracy);

  simulate->add_option(
      "--record", sim.record,
      "Write every node's position at every frame time k / fps to FILE (a recording the "
      "learning stage reads; docs/learning.md)");
  simulate->add_option(
      "--export-pc2", sim.export_pc2,
      "Write the frames as a PC2 point cache FILE.pc2 and the rest mesh as FILE.obj, for "
      "Blender's Mesh Cache modifier (docs/learning.md)");
  simulate->add_option("--threads", sim.threads,
                       "Threads sharing each step (results are identical; default 2 on a cloth "
                       "of 64x64 nodes or more when the machine has an idle second core, else 1)");
  simulate->add_option("--precision", sim.precision,
                       "The spring layer's arithmetic: double (the default) or float (faster, "
                       "explicit integrators only; docs/network.md, \"Float springs\")");
  simulate->add_option("--damping", sim.damping,
                       "The springs' damping: explicit (the paper's, in the force sum) or implicit "
                       "(spring by spring after the velocity update: larger stable steps on fine "
                       "cloths; network integrator only; docs/stability.md)");
  simulate->add_option("--step-bound", sim.step_bound,
                       "What caps the explicit steps: spectral (the default: the largest "
                       "eigenvalues by Lanczos) or gershgorin (per-node discs, smaller steps; "
                       "docs/stability.md)");
  simulate
      ->add_option("--safety", sim.safety,
                   "The adaptive step's cap as a fraction of the stability bound, in (0, 1] "
                   "(the scene's solver.safety, default 0.5; 1 halves the steps of a cloth "
                   "whose cap is reached; docs/stability.md)")
      ->excludes(accuracy);
  simulate->add_option("--size", sim.size,
                       "Run the scene's cloth resized to N x N, keeping its width and mass (as the "
                       "window's --size)");
  simulate->add_option("--record-fps", sim.record_fps,
                       "Frames per simulated second for --record and --export-pc2 (default 60)");

  TradeoffOptions trade;
  auto* tradeoff = app.add_subcommand(
      "tradeoff", "Measure speed against accuracy for every integrator; write CSV, chart, summary");
  tradeoff->add_option("scene", trade.scene, "Scene file (JSON)")->required();
  tradeoff->add_option("--seconds", trade.seconds, "Simulated seconds per run (default 2)");
  tradeoff->add_option("--out", trade.out, "REPORT: writes REPORT.csv, REPORT.png and REPORT.md")
      ->required();
  tradeoff->add_option("--samples", trade.samples,
                       "Times (evenly spaced) at which positions are compared (default 8)");
  tradeoff->add_option("--reference-budget", trade.reference_budget,
                       "Run seconds for halving the RK4 reference's step (default 20)");
  tradeoff->add_option("--method-budget", trade.method_budget,
                       "Run seconds for each method's sweep (default 8)");
  tradeoff->add_option("--levels", trade.levels, "Settings per method at most (default 7)");
  tradeoff
      ->add_option("--methods", trade.methods, "Only these (" + integrator_names() + ", adaptive)")
      ->delimiter(',');
  tradeoff
      ->add_option("--projective-iterations", trade.projective_iterations,
                   "Projective's iterations per step, each run at every step (default 1,2,4,10,30)")
      ->delimiter(',');
  tradeoff
      ->add_option("--vbd-iterations", trade.vbd_iterations,
                   "vbd's sweeps per step, each run at every step (default 4,10,30,100)")
      ->delimiter(',');
  tradeoff
      ->add_option("--implicit-tolerances", trade.implicit_tolerances,
                   "implicit_euler's CG tolerances (relative residual), each run at every step "
                   "(default 1e-10,1e-6,1e-3)")
      ->delimiter(',');
  tradeoff->add_option("--size", trade.size,
                       "Measure the scene's cloth resized to N x N (as the window's --size)");
  tradeoff
      ->add_option("--dt", trade.steps,
                   "Run the fixed-step methods at only these steps (s; e.g. 1/60), no halving")
      ->delimiter(',');
  tradeoff->add_option("--workers", trade.workers,
                       "Method lines measured at once, 1 to " +
                           std::to_string(kMaxTradeoffWorkers) +
                           " (default: one per core; 1: one after another)");
  tradeoff->add_option("--ensemble", trade.ensemble,
                       "References of the scene's own spread, each the cloth shifted by "
                       "--perturbation (default 8; 2 to 64)");
  tradeoff->add_option("--perturbation", trade.perturbation,
                       "Each reference's shift, in a seeded horizontal direction: 1mm (default), "
                       "0.5um, 1e-6 (m); 1 nm to 5 cm");
  tradeoff->add_option("--replot", trade.replot,
                       "Measure nothing: write REPORT.png and REPORT.md of this trade CSV (of "
                       "the scene) in --metric");
  tradeoff->add_option("--metric", trade.metric,
                       "The error the summary's budgets, front and chart use: " + metric_names() +
                           " (default " + to_string(kDefaultMetric) + ")");

  CompareOptions cmp;
  auto* compare = app.add_subcommand(
      "compare", "Every error metric between two results of one cloth, as JSON on stdout");
  compare->add_option("a", cmp.a, "RESULT.json (simulate's, relax's, or bench/peers' Blender's)")
      ->required();
  compare->add_option("b", cmp.b, "RESULT.json of the same cloth")->required();
  compare->add_option("--scene", cmp.scene,
                      "The scene (its triangles, support and size); default: the results' own; "
                      "given, it must have a box, sphere or cylinder to drape over");
  compare->add_option("--size", cmp.size,
                      "The scene's cloth resized to N x N (default: from the node count)");

  RelaxOptions rel;
  auto* relax = app.add_subcommand("relax", "Propagate to the local energy minimum (static drape)");
  relax->add_option("scene", rel.scene, "Scene file (JSON)")->required();
  relax->add_option("--out", rel.out, "Where to write RESULT.json")->required();

  BenchOptions bench;
  auto* bench_cmd = app.add_subcommand("bench", "Time the network step on an N x N cloth");
  bench_cmd->add_option("--size", bench.size, "N (cloth is N x N)");
  bench_cmd->add_option("--steps", bench.steps, "Steps per timed run");
  bench_cmd->add_option("--repeat", bench.repeat, "Timed runs; the median is reported");
  bench_cmd->add_option("--integrator", bench.integrator, "Integrator to time");
  bench_cmd->add_option("--threads", bench.threads,
                        "Threads sharing each step (default 1; results are identical)");
  bench_cmd->add_option("--precision", bench.precision,
                        "double (default), or float: the float spring layer timed beside the "
                        "double one in the same runs");
  bench_cmd->add_option("--kernel", bench.kernel,
                        "Spring kernel: auto (default; avx512 where the CPU has it), portable or "
                        "avx512; one named is timed beside the other in the same runs");
  bench_cmd->add_flag("--json", bench.json, "Print JSON");

  MaterialOptions mat;
  auto* material =
      app.add_subcommand("material", "Derive material parameters from linguistic inputs");
  auto* rules = material->add_option("--rules", mat.rules, "Rule base (FCL)");
  auto* inputs =
      material->add_option("--input", mat.inputs, "NAME=VALUE, one per input")->expected(1, -1);
  auto* preset =
      material->add_option("--preset", mat.preset, "A shipped preset (assets/materials/NAME.json)");
  auto* measured = material
                       ->add_option("--measured", mat.measured,
                                    "A fabric (assets/materials/fabrics/NAME.json) or KEY=VALUE "
                                    "... of material.measured: the weights it gives")
                       ->expected(1, -1);
  material->add_option("--spacing", mat.spacing, "Grid spacing the weights are shown for, m")
      ->needs(measured);
  preset->excludes(rules)->excludes(inputs);
  measured->excludes(rules)->excludes(inputs)->excludes(preset);
  rules->needs(inputs);
  material->add_flag("--json", mat.json, "Print JSON");
  material->callback([&] {
    if (mat.rules.empty() && !mat.preset && mat.measured.empty())
      throw CLI::RequiredError("--rules, --preset or --measured");
  });

  FitOptions fit;
  auto* fit_cmd = app.add_subcommand(
      "fit", "Fit the network's weights to a reference motion; write FITTED.json and its curves");
  fit_cmd->add_option("scene", fit.scene, "Scene file (JSON)")->required();
  auto* fit_reference =
      fit_cmd->add_option("--reference", fit.reference,
                          "The motion to fit: a recording (simulate --record), a marker CSV "
                          "(time,node,x,y,z), a point cloud (CSV time,x,y,z; a folder or a "
                          "numbered pattern of PLY / XYZ files), or a PC2 / MDD point cache");
  auto* fit_bending_length = fit_cmd->add_option(
      "--bending-length", fit.bending_length,
      "Instead of a reference: a cantilever test's bending length, m (the scene a cantilever: "
      "docs/materials.md); fit bending.rigidity to it");
  fit_cmd->add_option("--at", fit.at, "When the cantilever is read, s (default 1)")
      ->needs(fit_bending_length);
  fit_bending_length->excludes(fit_reference);
  fit_cmd->callback([&] {
    if (fit.reference.empty() && !fit.bending_length)
      throw CLI::RequiredError("--reference or --bending-length");
  });
  fit_cmd->add_option("--reference-fps", fit.reference_fps,
                      "Frames per second of PLY / XYZ frames or of a PC2 cache");
  fit_cmd->add_option(
      "--reference-start", fit.reference_start,
      "Time of the reference's first frame, s (PLY / XYZ frames, caches; default 0)");
  fit_cmd->add_option("--reference-mesh", fit.reference_mesh,
                      "The OBJ a PC2 / MDD cache deforms (its vertex k is node k)");
  fit_cmd->add_option("--chamfer", fit.chamfer,
                      "A point cloud's distance: two-sided (default) or one-sided (only the "
                      "points' own distances: a camera that sees part of the cloth)");
  fit_cmd->add_option("--robust", fit.robust,
                      "A point cloud's loss: none (squared distance, default), huber or cauchy "
                      "(outliers pull no harder than a point --robust-scale off)");
  fit_cmd->add_option("--robust-scale", fit.robust_scale,
                      "Where a robust loss stops growing as the square, m (default 0.01)");
  fit_cmd
      ->add_option("--params", fit.params,
                   "What to fit, comma-separated (default spring_constant,viscosity; "
                   "docs/learning.md lists the names)")
      ->delimiter(',');
  fit_cmd->add_flag("--per-element", fit.per_element,
                    "One weight per spring and node instead of one per family");
  fit_cmd->add_option("--smoothness", fit.smoothness,
                      "Strength of the smoothness regulariser on per-element weights (default 0)");
  fit_cmd->add_option("--path-smoothness", fit.path_smoothness,
                      "Strength of the smoothness term on a fitted path (pin_motion.keyframes: "
                      "its second differences, default 0)");
  fit_cmd->add_option("--global", fit.global,
                      "none (default) | es: first search the box around the start by forward "
                      "runs (an evolution strategy), then descend from the best it found");
  fit_cmd->add_option("--global-evaluations", fit.global_evaluations,
                      "Forward runs of the global search (default 200)");
  fit_cmd->add_option("--optimizer", fit.optimizer, "lbfgs (default) | gd (gradient descent)");
  fit_cmd->add_option("--max-iterations", fit.max_iterations, "At most this many (default 100)");
  fit_cmd->add_option("--time-budget", fit.time_budget,
                      "Stop after this many wall seconds (default: none)");
  fit_cmd->add_option("--tape-budget", fit.tape_budget_mb,
                      "MB the stored states may take before segments are recomputed (default 512)");
  fit_cmd->add_option("--out", fit.out, "FITTED.json (also FITTED.loss.csv, FITTED.loss.png)")
      ->required();
  fit_cmd
      ->add_flag("--online", fit.online,
                 "Adapt the weights while the reference plays (truncated BPTT per window)")
      ->excludes(fit_bending_length);
  fit_cmd->add_option("--window", fit.window, "Online: steps per back-propagation window (50)");
  fit_cmd->add_option("--learning-rate", fit.learning_rate,
                      "Online: the largest change of one parameter per window, log units (0.05)");

  TuneRulesOptions tune;
  auto* tune_cmd = app.add_subcommand(
      "tune-rules",
      "Tune a rule base's terms to examples of what it should give; write the tuned FCL");
  tune_cmd->add_option("--rules", tune.rules, "The rule base to tune (FCL, or MATLAB/Octave .fis)")
      ->required();
  tune_cmd
      ->add_option("--examples", tune.examples,
                   "CSV: a header naming every input and the outputs to tune, one example a row")
      ->required();
  tune_cmd->add_option("--out", tune.out, "OUT.fcl or OUT.fis (also OUT.examples.csv)")->required();
  tune_cmd
      ->add_option("--what", tune.what,
                   "mf (inputs' membership functions and Mamdani output sets; inputs or sets for "
                   "one half), consequents (Sugeno), or both (default)")
      ->delimiter(',');
  tune_cmd->add_option("--iterations", tune.iterations, "At most this many (default 500)");
  tune_cmd->add_option("--time", tune.time, "Stop after this many wall seconds (default: none)");

#ifdef NEUROCLOTH_HAS_SNAPSHOT
  SnapshotOptions snap;
  auto* snapshot = app.add_subcommand(
      "snapshot", "Render a scene after --seconds to a PNG, headless (no display needed)");
  snapshot->add_option("scene", snap.scene, "Scene file (JSON)")->required();
  snapshot->add_option("--seconds", snap.seconds,
                       "Simulated seconds before the picture (default 0)");
  snapshot->add_option("--out", snap.out, "Where to write the PNG")->required();
  snapshot->add_option("--size", snap.size, "WIDTHxHEIGHT in pixels (default 1280x720)");
  snapshot->add_option("--camera", snap.camera,
                       "yaw,pitch,distance[,tx,ty,tz] in radians and metres "
                       "(default: frames the cloth and its colliders)");
  snapshot->add_flag("--wireframe", snap.wireframe, "Draw the triangle edges");
  snapshot->add_flag("--springs", snap.springs, "Draw the springs coloured by family");
  snapshot->add_flag("--nodes", snap.nodes, "Draw the mass points (pinned ones red)");
  snapshot->add_flag("--strain", snap.strain, "Colour the cloth by stretch, with a legend");
  snapshot->add_option("--strain-max", snap.strain_max,
                       "Stretch at the red end of the strain map (default 0.1 = 10%)");
  snapshot->add_flag("--verbose", snap.verbose, "Report the OpenGL renderer and timings");
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitOk : kExitUsage;
  }
  // A mask of CPU features that cannot be read runs nothing (cpu_features.h).
  if (const std::string cpu = disabled_cpu_features_error(); !cpu.empty()) {
    std::fprintf(stderr, "error: %s\n", cpu.c_str());
    return kExitUsage;
  }
  try {
    if (*simulate) return run_simulate(sim);
    if (*tradeoff) return run_tradeoff(trade);
    if (*relax) return run_relax(rel);
    if (*compare) return run_compare(cmp);
    if (*bench_cmd) return run_bench(bench);
    if (*material) return run_material(mat);
    if (*fit_cmd) return run_fit(fit);
    if (*tune_cmd) return run_tune_rules(tune);
#ifdef NEUROCLOTH_HAS_SNAPSHOT
    if (*snapshot) return run_snapshot(snap);
#endif
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitInputError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return kExitInputError;
  }
  return kExitUsage;
}
