#pragma once
// The subcommands of neurocloth-cli. Each returns the process exit code:
// 0 ok, 3 diverged (result still written), 4 relax did not converge (result
// written), 5 simulate stopped early at its step budget (result written), 1 bad
// input (nothing written), 130 interrupted by Ctrl-C (result written, at the
// time reached; long_run.h).
#include <optional>
#include <string>
#include <vector>

#include "core/integrators/integrator.h"
#include "core/network/spring_precision.h"

namespace neurocloth {

inline constexpr int kExitOk = 0;
inline constexpr int kExitInputError = 1;
inline constexpr int kExitUsage = 2;
inline constexpr int kExitDiverged = 3;
inline constexpr int kExitNotConverged = 4;
// simulate: the step budget ran out before --seconds (the result is healthy, at
// an earlier time; docs/stability.md).
inline constexpr int kExitStoppedEarly = 5;

// --precision NAME as a SpringPrecision, or an InputError naming the option.
SpringPrecision precision_option(const std::string& name);

struct SimulateOptions {
  std::string scene;
  double seconds = 0;
  std::optional<std::string> integrator;
  std::optional<double> dt;
  std::optional<int> iterations;  // projective's local-global iterations or vbd's sweeps per step
  bool adaptive = false;
  bool fixed_step = false;
  std::string out;
  // --accuracy E: the cheapest setting the measured trade says keeps the max position
  // error within E of the cloth's size; from --trade FILE.csv, else the committed
  // assets/tradeoff/<scene stem>.csv, else measured first (tradeoff_command.cpp).
  // With --size N the committed trade is assets/tradeoff/<stem>.<N>.csv. It picks
  // against max(E, the trade's floor) in --metric (default: the trade's default).
  std::optional<double> accuracy;
  std::optional<std::string> trade;
  std::optional<std::string> metric;
  double progress = 2;  // wall seconds between progress lines on stderr; 0: none
  // --record FILE: every node at every frame time k / fps, in the file's node
  // order (docs/learning.md, "Reference motion"); --export-pc2 FILE.pc2: the
  // same frames as a PC2 point cache, with the rest mesh as FILE.obj.
  std::optional<std::string> record;
  std::optional<std::string> export_pc2;
  std::optional<double> record_fps;  // default 60
  // --threads N: threads sharing each step (results identical); default
  // batch_step_threads (step_threads.h).
  std::optional<int> threads;
  // --precision double|float: the scene's solver.precision, overridden.
  std::optional<std::string> precision;
  // --damping explicit|implicit: the scene's solver.damping, overridden.
  std::optional<std::string> damping;
  // --step-bound spectral|gershgorin: the scene's solver.step_bound, overridden.
  std::optional<std::string> step_bound;
  // --safety S: the scene's solver.safety (the adaptive cap as a fraction of
  // the stability bound), overridden.
  std::optional<double> safety;
  std::optional<int> size;  // --size N: sized_scene
};
int run_simulate(const SimulateOptions& options);

// Measures the speed-against-accuracy trade of a scene and writes REPORT.csv,
// REPORT.png (the chart) and REPORT.md (the summary); docs/tradeoff.md.
struct TradeoffOptions {
  std::string scene;
  double seconds = 2;
  std::string out;  // REPORT: the three files' common path without extension
  int samples = 8;
  double reference_budget = 20;             // run cost seconds for the RK4 reference's halvings
  double method_budget = 8;                 // run cost seconds per method's sweep
  int levels = 7;                           // settings per method at most
  std::vector<std::string> methods;         // empty: all
  std::vector<int> projective_iterations;   // empty: the sweep's own grid
  std::vector<int> vbd_iterations;          // empty: the sweep's own grid
  std::vector<double> implicit_tolerances;  // empty: the sweep's own grid
  // --size N: the scene's cloth resized to N x N (resized_grid), as the window's
  // --size runs it; the trade then holds at that size only.
  std::optional<int> size;
  // --dt: the only steps the fixed-step methods run, each "0.01" or "1/60" (s).
  std::vector<std::string> steps;
  // --workers N: method lines measured at once (1: one after another); default
  // one per core (TradeoffPlan::workers).
  std::optional<int> workers;
  // --ensemble K: references of the scene's own spread (default 8, in [2, 64]);
  // --perturbation: each one's shift ("1mm", "1e-6", "0.5um"; default 1 mm);
  // --metric: what the summary's budgets, front and chart use.
  int ensemble = 8;
  std::string perturbation = "1mm";
  std::string metric;  // empty: kDefaultMetric
  // --replot FILE.csv: no measuring; the chart and summary of a trade already
  // measured (of this scene), in --metric.
  std::optional<std::string> replot;
};
int run_tradeoff(const TradeoffOptions& options);
struct Scene;
// --size N (simulate, tradeoff): the scene's cloth resized to N x N
// (resized_grid), as the window's --size runs it; without N, the scene as
// read. A size out of range or a scene with no grid is an InputError.
Scene sized_scene(Scene scene, const std::string& scene_path, const std::optional<int>& size);
// A length as "1mm", "0.5um", "2nm", "1cm" or "1e-6" (m); nullopt when it is none.
std::optional<double> parse_length(const std::string& text);
// --metric's value (empty: kDefaultMetric); an unknown name is an InputError naming `option`.
enum class Metric : int;
Metric metric_option(const std::string& text, const char* option);
// The parts `simulate --accuracy` shares when it has to measure a trade itself:
// the checked plan (InputError naming the option) and the measurement, which
// prints its progress on stdout.
struct TradeoffPlan;
struct TradeTable;
TradeoffPlan tradeoff_plan(const TradeoffOptions& options);
TradeTable measure_trade(const Scene& scene, const std::string& scene_file,
                         const TradeoffPlan& plan);

// `compare A.json B.json [--scene S] [--size N]`: every metric between two
// results of one cloth, as JSON on stdout (compare_command.cpp).
struct CompareOptions {
  std::string a, b;
  std::optional<std::string> scene;  // default: the results' own "scene"
  std::optional<int> size;           // default: from their node count
};
int run_compare(const CompareOptions& options);

struct RelaxOptions {
  std::string scene;
  std::string out;
};
int run_relax(const RelaxOptions& options);

struct BenchOptions {
  int size = 64;
  int steps = 200;
  int repeat = 5;
  std::string integrator = "network";
  int threads = 1;  // SolverSettings::threads
  // "double", or "float": the float step timed beside the double one in the
  // same runs (SolverSettings::precision).
  std::string precision = "double";
  // "auto" (the default: AVX-512 where the CPU has it), "portable" or "avx512"
  // (SolverSettings::kernel). A kernel named where both can run is timed
  // beside the other one in the same runs.
  std::string kernel = "auto";
  bool json = false;
};
int run_bench(const BenchOptions& options);

struct MaterialOptions {
  std::string rules;                  // --rules FILE.fcl
  std::vector<std::string> inputs;    // --input NAME=VALUE ...
  std::optional<std::string> preset;  // --preset NAME
  // --measured NAME (a fabric, assets/materials/fabrics) or KEY=VALUE ... (the
  // keys of a scene's material.measured): the network's weights for it.
  std::vector<std::string> measured;
  double spacing = 0.01;  // --spacing: the grid the weights are shown for, m
  bool json = false;
};
int run_material(const MaterialOptions& options);

// Renders a scene after `seconds` to a PNG without a display (OSMesa). Built
// only with NEUROCLOTH_BUILD_VIEWER (snapshot_command.cpp).
struct SnapshotOptions {
  std::string scene;
  double seconds = 0;
  std::string out;                    // FILE.png
  std::string size = "1280x720";      // WIDTHxHEIGHT
  std::optional<std::string> camera;  // yaw,pitch,distance[,tx,ty,tz]; default frames the scene
  bool wireframe = false;
  bool springs = false;
  bool nodes = false;
  bool strain = false;
  std::optional<double> strain_max;  // the red end of the strain map, as a fraction
  bool verbose = false;
};
int run_snapshot(const SnapshotOptions& options);

// Fits the network's weights to a reference motion (paper eq. 18-19) and writes
// FITTED.json (a scene simulate and the viewer load as is), its side file of
// per-element weights, FITTED.loss.csv and FITTED.loss.png (docs/learning.md).
// Exit codes: 0 the fit stopped at a tolerance, a budget or a failed line
// search (the best parameters are written); 3 a loss or gradient came back
// NaN (the best parameters before it are written); 130 Ctrl-C (the best so far
// written); 1 bad input (nothing written).
struct FitOptions {
  std::string scene;
  std::string reference;  // --reference: a recording, a CSV, PLY/XYZ frames, a cache
  // --bending-length: a cantilever test's reading instead of a reference
  // (fabric_test_reference.h), read at --at seconds.
  std::optional<double> bending_length;
  double at = 1.0;
  double reference_fps = 0;           // --reference-fps: a frame sequence's or a PC2's rate
  double reference_start = 0;         // --reference-start: the first frame's time, s
  std::string reference_mesh;         // --reference-mesh: the OBJ a PC2 / MDD cache deforms
  std::string chamfer = "two-sided";  // --chamfer two-sided | one-sided (point clouds)
  std::string robust = "none";        // --robust none | huber | cauchy (point clouds)
  double robust_scale = 0.01;         // --robust-scale, m
  std::vector<std::string> params;    // --params a,b,...; empty: spring_constant, viscosity
  bool per_element = false;           // --per-element
  double smoothness = 0;              // --smoothness: the per-element regulariser's strength
  double path_smoothness = 0;         // --path-smoothness: a fitted path's second differences
  std::string global = "none";        // --global none | es: a global first stage
  int global_evaluations = 200;       // --global-evaluations: its forward runs
  std::string optimizer = "lbfgs";    // --optimizer lbfgs | gd
  int max_iterations = 100;           // --max-iterations, >= 1
  double time_budget = 0;             // --time-budget, wall seconds; 0: none
  double tape_budget_mb = 512;        // --tape-budget, MB of checkpoints
  std::string out;                    // --out FITTED.json
  bool online = false;                // --online: fit while the motion plays (fit_online.cpp)
  int window = 50;                    // --window: steps per online window (W)
  double learning_rate = 0.05;        // --learning-rate: online step per window (log units)
};
int run_fit(const FitOptions& options);
// The online mode (--online), in fit_online.cpp; run_fit checks the options both share first.
int run_fit_online(const FitOptions& options);
// What both modes build from the options: the reference read for `scene` and the
// fit problem (InputError naming the file or option). fit_command.cpp.
class FitProblem;
FitProblem load_fit_problem(const FitOptions& options, const Scene& scene);
// Refuses an output of the fit (FITTED.json and its companions) that is one of
// the files `scene` was read from (InputError naming --out).
void check_fit_outputs(const FitOptions& options, const Scene& scene);

// Tunes a rule base's terms to examples of what it should give and writes the
// tuned FCL and OUT.examples.csv (docs/learning.md, "Tuning a rule base from
// examples"). Exit codes: 0 done (the best rule base is written); 3 a loss
// came back NaN (the best before it written); 130 Ctrl-C (the best so far
// written); 1 bad input (nothing written).
struct TuneRulesOptions {
  std::string rules;              // --rules IN.fcl
  std::string examples;           // --examples EXAMPLES.csv
  std::string out;                // --out OUT.fcl (and OUT.examples.csv)
  std::vector<std::string> what;  // --what mf|inputs|sets,consequents; empty: mf,consequents
  int iterations = 500;           // --iterations, 1 .. 1e6
  double time = 0;                // --time, wall seconds; 0: none
};
int run_tune_rules(const TuneRulesOptions& options);

}  // namespace neurocloth
