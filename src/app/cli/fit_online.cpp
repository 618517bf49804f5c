// neurocloth-cli fit --online: the paper's online adaptation (the options
// common to fit were checked by run_fit). The cloth runs
// through the reference's time once; after every window of W steps the error
// over that window is back-propagated through it and the weights move once
// (online_adaptation.h). Writes FITTED.json with the weights at the end, and the
// per-window curve (docs/learning.md, "Online adaptation").
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "app/cli/commands.h"
#include "app/cli/long_run.h"
#include "chart/loglog_chart.h"
#include "core/io/input_error.h"
#include "core/scene/scene.h"
#include "learn/fit/fit_columns.h"
#include "learn/fit/fit_problem.h"
#include "learn/fit/fitted_output.h"
#include "learn/fit/online_adaptation.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {

int run_fit_online(const FitOptions& o) {
  if (o.window < 1 || o.window > 1000000)
    throw InputError("command line", "--window", "must be a number of steps in [1, 1000000]");
  if (!(o.learning_rate > 0 && o.learning_rate <= 10))
    throw InputError("command line", "--learning-rate",
                     "must be in (0, 10] (the largest change of one parameter per window, in log "
                     "units for positive ones)");
  const Scene scene = load_scene(o.scene);
  FitProblem problem = load_fit_problem(o, scene);
  OnlineAdaptation online(problem, {static_cast<std::size_t>(o.window), o.learning_rate});
  std::printf("fit --online: %s to %s: %zu unknowns, windows of %d steps, learning rate %g\n",
              scene.name.c_str(), o.reference.c_str(), problem.size(), o.window, o.learning_rate);

  FitHistory history;
  history.columns = block_names(problem);
  auto columns = [&](const Eigen::VectorXd& theta) { return block_values(problem, theta); };
  const bool terminal = isatty(fileno(stdout)) != 0;
  const InterruptScope ctrl_c;
  int windows = 0;
  double last_rms = 0, last_loss = 0;
  bool interrupted = false, blew_up = false;
  while (!online.done()) {
    if (InterruptScope::interrupted()) {
      interrupted = true;
      break;
    }
    const OnlineAdaptation::Update u = online.advance();
    ++windows;
    if (!std::isfinite(u.loss)) {
      blew_up = true;
      break;
    }
    if (u.observed == 0) continue;
    last_rms = u.rms_m;
    last_loss = u.loss;
    const std::vector<double> values = columns(problem.inside_limits(online.theta()));
    history.rows.push_back({windows, u.loss, u.rms_m, u.time, values});
    std::string line;
    char buf[96];
    std::snprintf(buf, sizeof buf, "t %.4g s  window loss %.4g  RMS %.4g mm", u.time, u.loss,
                  u.rms_m * 1e3);
    line = buf;
    for (std::size_t c = 0; c < values.size(); ++c) {
      std::snprintf(buf, sizeof buf, "  %s %.5g", history.columns[c].c_str(), values[c]);
      line += buf;
    }
    if (terminal)
      std::printf("\r%s\x1b[K", line.c_str());
    else
      std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  }
  if (terminal) std::printf("\n");
  if (blew_up)
    std::printf("stopped: the cloth blew up with the weights of the last window; kept those\n");
  FitSummary summary;
  summary.reference = o.reference;
  summary.optimizer = "online (truncated BPTT, window " + std::to_string(o.window) +
                      " steps, learning rate " + std::to_string(o.learning_rate) + ")";
  summary.stop_reason = interrupted ? "stopped" : blew_up ? "not_finite" : "reference_end";
  summary.stop_message = interrupted ? "interrupted (Ctrl-C)"
                         : blew_up   ? "a window's loss was not finite"
                                     : "the reference ended";
  summary.iterations = windows;
  summary.loss = last_loss;
  summary.rms_m = last_rms;
  const std::vector<double> values = columns(problem.inside_limits(online.theta()));
  for (std::size_t c = 0; c < values.size(); ++c) {
    ParameterUncertainty p;
    p.name = history.columns[c];
    p.value = values[c];
    p.sd = p.relative_sd = std::nan("");
    summary.parameters.push_back(p);
  }
  summary.uncertainty = "not estimated: an online fit ends wherever the reference ends";
  summary.words = problem.inputs_in_words(online.theta());
  for (const std::string& w : summary.words)
    std::printf("in words: %s\n", w.c_str());
  const FittedModel model{problem.fitted_scene(online.theta()),
                          problem.element_weights(online.theta()),
                          problem.element_rest_lengths(online.theta())};
  const FittedFiles files = write_fit_outputs(scene, model, summary, history, o.out);
  release_chart_caches();  // the one chart of this process is drawn
  std::printf("wrote %s, %s, %s (last window RMS %.4g mm)\n", files.scene.c_str(),
              files.csv.c_str(), files.png.c_str(), last_rms * 1e3);
  return interrupted ? kExitInterrupted : blew_up ? kExitDiverged : kExitOk;
}

}  // namespace neurocloth
