// neurocloth-cli fit: the network's weights fitted to a reference motion
// (paper eq. 18-19) by L-BFGS or gradient descent, the parameters' uncertainty
// at the optimum, and FITTED.json with its curves (docs/learning.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "app/cli/commands.h"
#include "app/cli/long_run.h"
#include "app/cli/motion_outputs.h"
#include "app/cli/progress_line.h"
#include "chart/loglog_chart.h"
#include "core/io/input_error.h"
#include "core/scene/scene.h"
#include "learn/fit/chamfer.h"
#include "learn/fit/fit_columns.h"
#include "learn/fit/fit_problem.h"
#include "learn/fit/fitted_output.h"
#include "learn/fit/input_starts.h"
#include "learn/motion/fabric_test_reference.h"
#include "learn/motion/read_reference.h"
#include "learn/motion/reference_motion.h"
#include "learn/optim/global_search.h"
#include "learn/optim/optimizer.h"
#include "learn/optim/uncertainty.h"

namespace neurocloth {
namespace {

// Every option checked before anything is read or run: InputError naming it.
OptimizerMethod check_options(const FitOptions& o) {
  auto refuse = [](const char* field, const std::string& why) {
    throw InputError("command line", field, why);
  };
  OptimizerMethod method{};
  if (!parse_optimizer_method(o.optimizer, method))
    refuse("--optimizer", "unknown optimizer '" + o.optimizer + "' (expected lbfgs or gd)");
  if (o.max_iterations < 1)
    refuse("--max-iterations", "must be at least 1 (got " + std::to_string(o.max_iterations) + ")");
  if (!(o.time_budget >= 0) || !std::isfinite(o.time_budget))
    refuse("--time-budget", "must be a finite number of seconds >= 0 (0: none)");
  if (!(o.smoothness >= 0) || !std::isfinite(o.smoothness))
    refuse("--smoothness", "must be a finite number >= 0");
  if (o.smoothness > 0 && !o.per_element)
    refuse("--smoothness", "smooths per-element weights: it needs --per-element");
  if (o.smoothness > 0 && o.online)
    refuse("--smoothness", "an online fit has no regulariser: drop --smoothness or --online");
  if (!(o.path_smoothness >= 0) || !std::isfinite(o.path_smoothness))
    refuse("--path-smoothness", "must be a finite number >= 0");
  if (o.path_smoothness > 0 && o.online)
    refuse("--path-smoothness",
           "an online fit has no regulariser: drop --path-smoothness or --online");
  if (o.online && std::find(o.params.begin(), o.params.end(), "initial_velocity") != o.params.end())
    refuse("--params",
           "an online fit adapts while the cloth runs: it has no initial velocity to "
           "fit (drop initial_velocity or --online)");
  if (o.global != "none" && o.global != "es")
    refuse("--global", "unknown search '" + o.global + "' (expected none or es)");
  if (o.global_evaluations < 1 || o.global_evaluations > 1000000)
    refuse("--global-evaluations", "must be a number of runs in [1, 1000000]");
  if (o.global != "none" && o.online)
    refuse("--global", "an online fit adapts as the motion plays: drop --global or --online");
  if (!(o.tape_budget_mb > 0) || !(o.tape_budget_mb < 1e9))
    refuse("--tape-budget", "must be a number of MB > 0");
  if (!(o.reference_fps >= 0) || !(o.reference_fps <= 1e6))
    refuse("--reference-fps", "must be a number of frames per second in (0, 1e6]");
  if (!std::isfinite(o.reference_start) || !(o.reference_start >= 0))
    refuse("--reference-start", "must be a finite number of seconds >= 0");
  if (o.chamfer != "two-sided" && o.chamfer != "one-sided")
    refuse("--chamfer", "unknown distance '" + o.chamfer + "' (expected two-sided or one-sided)");
  RobustLoss robust{};
  if (!parse_robust_loss(o.robust, robust))
    refuse("--robust", "unknown loss '" + o.robust + "' (expected none, huber or cauchy)");
  if (!(o.robust_scale > 0) || !(o.robust_scale <= 1e3))
    refuse("--robust-scale", "must be a distance in m in (0, 1000]");
  if (o.out.empty()) refuse("--out", "must name the FITTED.json to write");
  const std::filesystem::path folder = std::filesystem::absolute(o.out).parent_path();
  if (!std::filesystem::is_directory(folder))
    refuse("--out", "the folder " + folder.string() + " does not exist");
  const FittedFiles files = fitted_file_names(o.out);
  for (const std::string& f : {files.scene, files.weights, files.csv, files.png, files.example})
    check_output_path("--out", f, {o.scene, o.reference, o.reference_mesh});
  return method;
}

}  // namespace

// Once the scene is read: its side files are inputs too.
void check_fit_outputs(const FitOptions& o, const Scene& scene) {
  const FittedFiles files = fitted_file_names(o.out);
  for (const std::string& f : {files.scene, files.weights, files.csv, files.png, files.example})
    check_output_path("--out", f, input_files(scene));
}

namespace {

// The fit's fields of the progress line: loss, RMS and each column's value.
std::string progress_details(const IterationInfo& it, double rms_m,
                             const std::vector<std::string>& columns,
                             const std::vector<double>& values) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "loss %.6g  RMS %.4g mm", it.loss, rms_m * 1e3);
  std::string line = buf;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    std::snprintf(buf, sizeof buf, "  %s %.5g", columns[c].c_str(), values[c]);
    line += buf;
  }
  return line;
}

std::vector<UncertainParameter> unknowns_of(const FitProblem& problem) {
  std::vector<UncertainParameter> out(problem.size());
  for (const FitBlock& b : problem.blocks())
    for (std::size_t i = 0; i < b.count; ++i)
      out[b.offset + i] = {b.count == 1 ? b.name : b.name + "[" + std::to_string(i) + "]",
                           b.log_space};
  return out;
}

void print_uncertainty(const UncertaintyReport& r, const FitProblem& problem) {
  if (!r.computed) {
    std::printf("uncertainty: %s\n", r.skipped.c_str());
    return;
  }
  std::printf(
      "uncertainty (Gauss-Newton: covariance = s^2 H^-1, s^2 = 2E/(N-P) = %.4g m^2, N = %zu, "
      "%d gradient calls):\n",
      r.residual_variance, r.data, r.gradient_calls);
  std::vector<std::string> units(problem.size());
  for (const FitBlock& b : problem.blocks())
    for (std::size_t i = 0; i < b.count; ++i)
      units[b.offset + i] = b.unit;
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const ParameterUncertainty& p = r.parameters[i];
    std::printf("  %-24s %12.6g %-6s +- %-10.3g (%6.3g%%)  %s\n", p.name.c_str(), p.value,
                units[i].c_str(), p.sd, 100 * p.relative_sd, to_string(p.verdict));
  }
  if (r.flat_directions > 0)
    std::printf(
        "  %d direction(s) the data does not see: the parameters marked 'not determined' can "
        "change together without changing the motion\n",
        r.flat_directions);
}

// The note's parameter list: each unknown with its uncertainty when there is
// one, else each column's value.
std::vector<ParameterUncertainty> summary_parameters(const UncertaintyReport& r,
                                                     const std::vector<std::string>& columns,
                                                     const std::vector<double>& values) {
  if (r.computed) return r.parameters;
  std::vector<ParameterUncertainty> out;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    ParameterUncertainty p;
    p.name = columns[c];
    p.value = values[c];
    p.sd = p.relative_sd = std::nan("");
    out.push_back(p);
  }
  return out;
}

// What the fit matched, for its report and FITTED.json.
std::string reference_name(const FitOptions& o) {
  if (!o.bending_length) return o.reference;
  return "cantilever bending length " + show_number(*o.bending_length) + " m at " +
         show_number(o.at) + " s";
}

int exit_code(StopReason reason) {
  switch (reason) {
    case StopReason::stopped:
      return kExitInterrupted;
    case StopReason::not_finite:
      return kExitDiverged;
    default:
      return kExitOk;
  }
}

}  // namespace

// Checks the outputs against the scene's inputs first (check_fit_outputs).
FitProblem load_fit_problem(const FitOptions& o, const Scene& scene) {
  check_fit_outputs(o, scene);
  ReferenceOptions ro;
  ro.fps = o.reference_fps;
  ro.start = o.reference_start;
  ro.mesh = o.reference_mesh;
  ro.scene_positions = file_order_positions(scene);
  const ReferenceMotion reference =
      o.bending_length ? cantilever_reference(scene, *o.bending_length, o.at, "--bending-length")
                       : read_reference(o.reference, scene.topology.rest_positions.size(), ro);
  if (!reference.note.empty()) std::printf("reference: %s\n", reference.note.c_str());
  FitSettings settings;
  settings.chamfer.one_sided = o.chamfer == "one-sided";
  parse_robust_loss(o.robust, settings.chamfer.robust);
  settings.chamfer.scale = o.robust_scale;
  if (!o.params.empty()) settings.params = o.params;
  settings.per_element = o.per_element;
  settings.smoothness = o.smoothness;
  settings.path_smoothness = o.path_smoothness;
  settings.tape_budget_bytes = std::size_t(o.tape_budget_mb * double(1 << 20));
  return FitProblem(scene, reference, settings);
}

int run_fit(const FitOptions& o) {
  // The online mode shares the tape budget and the outputs: checked before
  // anything runs, whichever mode.
  OptimizerOptions opt;
  opt.method = check_options(o);
  if (o.online) return run_fit_online(o);
  opt.max_iterations = o.max_iterations;
  opt.time_budget = o.time_budget;

  const Scene scene = load_scene(o.scene);
  FitProblem problem = load_fit_problem(o, scene);
  const std::vector<std::string> columns = block_names(problem);
  const double observations = double(problem.observations());
  std::printf("fit: %s to %s: %zu unknowns, %zu observed %s over %g s, %s\n", scene.name.c_str(),
              reference_name(o).c_str(), problem.size(), problem.observations(),
              problem.fits_cloud() ? "points (Chamfer distance)" : "positions", problem.duration(),
              to_string(opt.method));
  std::fflush(stdout);

  const Objective objective = [&](const Eigen::VectorXd& theta, Eigen::VectorXd* gradient) {
    return problem.loss(theta, gradient);
  };
  // The data term's RMS: from the loss itself when there is no regulariser.
  auto rms_of = [&](double loss, const Eigen::VectorXd& theta) {
    return o.smoothness > 0 || o.path_smoothness > 0 ? problem.rms_error(theta)
                                                     : std::sqrt(2 * loss / observations);
  };
  FitHistory history;
  history.columns = columns;
  ProgressLine progress(o.max_iterations, o.time_budget);
  const InterruptScope ctrl_c;
  opt.should_stop = [] { return InterruptScope::interrupted(); };
  GlobalSearchOptions global;
  global.evaluations = o.global_evaluations;
  global.should_stop = [] { return InterruptScope::interrupted(); };
  const InputStarts starts =
      o.global == "es" ? global_fit_starts(problem, global) : input_fit_starts(problem);
  if (!starts.said.empty()) std::printf("%s\n", starts.said.c_str());
  const OptimizerResult result =
      minimize_from(objective, starts.starts, opt, [&](const IterationInfo& it) {
        const Eigen::VectorXd theta = problem.inside_limits(it.theta);
        FitHistoryRow row{it.iteration, it.loss, rms_of(it.loss, theta), it.seconds,
                          block_values(problem, theta)};
        history.rows.push_back(row);
        progress.show(it, progress_details(it, row.rms_m, columns, row.parameters));
        return !InterruptScope::interrupted();
      });
  progress.close();
  std::printf("stopped (%s): %s\n", to_string(result.reason), result.message.c_str());
  std::printf("memory: the tape held at most %.3g MB (--tape-budget %g MB)\n",
              double(problem.peak_tape_bytes()) / double(1 << 20), o.tape_budget_mb);
  if (std::isnan(result.best_loss) && result.reason == StopReason::stopped) {
    std::fprintf(stderr, "interrupted before the first evaluation; nothing written\n");
    return kExitInterrupted;
  }
  if (std::isnan(result.best_loss)) {
    std::fprintf(stderr,
                 "error: the scene's own parameters already give a non-finite loss; nothing "
                 "written\n");
    return kExitDiverged;
  }
  // The loss at theta is the loss inside the limits: the values written.
  const Eigen::VectorXd best = problem.inside_limits(result.best_theta);

  UncertaintyReport uncertainty;
  if (result.reason == StopReason::stopped) {
    uncertainty.skipped = "not estimated: the fit was interrupted";
  } else {
    // A point's distance to the surface is one number (along the normal); a
    // node's offset from its marker is three.
    const std::size_t residuals = (problem.fits_cloud() ? 1 : 3) * problem.observations();
    uncertainty =
        estimate_uncertainty(objective, best, result.best_loss, residuals, unknowns_of(problem));
    if (!uncertainty.computed && uncertainty.skipped.empty()) uncertainty.skipped = "not estimated";
  }
  print_uncertainty(uncertainty, problem);
  const std::vector<std::string> words = problem.inputs_in_words(best);
  for (const std::string& w : words)
    std::printf("in words: %s\n", w.c_str());

  FitSummary summary;
  summary.reference = reference_name(o);
  summary.optimizer = to_string(opt.method);
  summary.stop_reason = to_string(result.reason);
  summary.stop_message = result.message;
  summary.iterations = result.iterations;
  summary.loss = result.best_loss;
  summary.rms_m = rms_of(result.best_loss, best);
  summary.parameters = summary_parameters(uncertainty, columns, block_values(problem, best));
  summary.words = words;
  summary.uncertainty =
      uncertainty.computed
          ? "Gauss-Newton: covariance = s^2 H^-1 with H by central differences of the gradient"
          : uncertainty.skipped;
  const FittedModel model{problem.fitted_scene(best), problem.element_weights(best),
                          problem.element_rest_lengths(best)};
  const FittedFiles files = write_fit_outputs(scene, model, summary, history, o.out);
  release_chart_caches();  // the one chart of this process is drawn
  std::printf("wrote %s%s%s, %s, %s (loss %.6g, RMS %.4g mm)\n", files.scene.c_str(),
              files.weights.empty() ? "" : ", ", files.weights.c_str(), files.csv.c_str(),
              files.png.c_str(), summary.loss, summary.rms_m * 1e3);
  if (!files.example.empty())
    std::printf(
        "wrote %s: this fit as an example for tune-rules (the scene's words and the "
        "fitted values)\n",
        files.example.c_str());
  return exit_code(result.reason);
}

}  // namespace neurocloth
