#include "runtime/fit_worker.h"

#include <cmath>
#include <exception>

#include "learn/fit/fit_columns.h"
#include "learn/fit/input_starts.h"

namespace neurocloth {

namespace {

// Blocks the material holds (fit_problem.h names them); anything else is a
// module parameter, named as the window names it ("wind.velocity.x").
bool material_block(const std::string& name) {
  for (const char* m :
       {"spring_constant", "shear_constant", "bend_constant", "viscosity", "node_mass", "friction"})
    if (name == m) return true;
  return false;
}

}  // namespace

const char* to_string(FitProgress::State state) {
  switch (state) {
    case FitProgress::State::idle:
      return "idle";
    case FitProgress::State::running:
      return "running";
    case FitProgress::State::finished:
      return "finished";
    case FitProgress::State::failed:
      return "failed";
  }
  return "?";
}

FitOutcome fit_outcome(const FitProblem& problem, const Scene& scene,
                       const Eigen::VectorXd& theta) {
  FitOutcome out;
  out.command.material = problem.fitted_scene(theta).material;
  out.words = problem.inputs_in_words(theta);
  const ParameterNames names = parameter_names(scene);
  const std::vector<double> values = block_values(problem, theta);
  for (std::size_t c = 0; c < problem.blocks().size(); ++c) {
    const FitBlock& b = problem.blocks()[c];
    if (material_block(b.name) && b.count == 1) continue;  // in the material
    if (b.count != 1) {
      out.not_applied.push_back(b.name + ": per element (the live cloth takes one value)");
      continue;
    }
    if (b.name == "rest_length") {
      out.not_applied.push_back(b.name + ": the live cloth keeps its rest lengths");
      continue;
    }
    if (const std::optional<ParameterId> id = parse_parameter(b.name, names))
      (id->kind == ParameterId::Kind::input ? out.command.inputs : out.command.module_parameters)
          .push_back({*id, values[c]});
    else
      out.not_applied.push_back(b.name + ": not a live parameter");
  }
  return out;
}

FitWorker::FitWorker(std::function<void(int)> on_row) : on_row_(std::move(on_row)) {}

FitWorker::~FitWorker() {
  stop();
  if (thread_.joinable()) thread_.join();
}

template <class Change>
void FitWorker::update(Change&& change) {
  std::lock_guard<std::mutex> lock(mutex_);
  change(progress_);
  progress_.serial = serial_.load(std::memory_order_relaxed) + 1;
  serial_.store(progress_.serial, std::memory_order_release);
}

std::string FitWorker::start(FitJob job) {
  if (!job.scene) return "no scene to fit";
  if (!job.reference) return "no reference loaded: load a recording or markers first";
  if (job.max_iterations < 1) return "max iterations must be at least 1";
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (running_) return "a fit is running: stop it first";
    running_ = true;
  }
  // The previous worker has finished (running_ was false): joining returns at once.
  if (thread_.joinable()) thread_.join();
  stop_.store(false);
  const long id = ++jobs_;
  update([&](FitProgress& p) {
    p = FitProgress{};
    p.state = FitProgress::State::running;
    p.job = id;
    p.online = job.online;
  });
  thread_ = std::thread([this, job = std::move(job)]() mutable { run(std::move(job)); });
  return "";
}

void FitWorker::stop() {
  stop_.store(true);
}

bool FitWorker::running() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return running_;
}

FitProgress FitWorker::progress() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return progress_;
}

void FitWorker::wait() const {
  std::unique_lock<std::mutex> lock(mutex_);
  done_.wait(lock, [this] { return !running_; });
}

void FitWorker::finish(FitProgress::State state, std::string message,
                       std::optional<StopReason> reason,
                       std::shared_ptr<const FitOutcome> outcome) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    progress_.state = state;
    progress_.message = std::move(message);
    progress_.reason = reason;
    if (outcome) progress_.outcome = std::move(outcome);
    progress_.serial = serial_.load(std::memory_order_relaxed) + 1;
    serial_.store(progress_.serial, std::memory_order_release);
    running_ = false;
  }
  done_.notify_all();
}

// Nothing escapes the thread: a scene that cannot be fitted, or anything the
// fit throws, ends the job as failed with the message.
void FitWorker::run(FitJob job) {
  try {
    FitProblem problem(*job.scene, *job.reference, job.settings);
    update([&](FitProgress& p) {
      p.names = block_names(problem);
      for (const FitBlock& b : problem.blocks())
        p.units.push_back(b.unit);
      p.values.resize(p.names.size());
      p.duration = problem.duration();
    });
    if (job.online)
      run_online(problem, job);
    else
      run_batch(problem, job);
  } catch (const std::exception& e) {
    finish(FitProgress::State::failed, e.what(), std::nullopt);
  }
}

void FitWorker::publish_row(FitProblem& problem, const Scene& scene, const Eigen::VectorXd& theta,
                            double loss, double rms, int iteration, double online_time) {
  auto outcome = std::make_shared<const FitOutcome>(fit_outcome(problem, scene, theta));
  const std::vector<double> values = block_values(problem, theta);
  int row = 0;
  update([&](FitProgress& p) {
    for (std::size_t c = 0; c < values.size(); ++c)
      p.values[c].push_back(values[c]);
    p.loss.push_back(loss);
    p.rms_m.push_back(rms);
    p.iteration = iteration;
    p.online_time = online_time;
    p.outcome = std::move(outcome);
    row = static_cast<int>(p.loss.size()) - 1;
  });
  if (on_row_) on_row_(row);
}

void FitWorker::run_batch(FitProblem& problem, const FitJob& job) {
  OptimizerOptions options;
  options.method = job.method;
  options.max_iterations = job.max_iterations;
  options.should_stop = [this] { return stop_.load(); };
  const double observations = std::max(1.0, double(problem.observations()));
  const OptimizerResult result =
      minimize_from([&](const Eigen::VectorXd& theta,
                        Eigen::VectorXd* gradient) { return problem.loss(theta, gradient); },
                    input_fit_starts(problem).starts, options,
                    [&](const IterationInfo& it) {
                      if (std::isfinite(it.loss))
                        publish_row(problem, *job.scene, it.theta, it.loss,
                                    std::sqrt(2 * it.loss / observations), it.iteration, 0);
                      return true;
                    });
  if (!std::isfinite(result.best_loss)) {
    finish(FitProgress::State::failed,
           "the scene's own parameters give a loss that is not finite (the run diverges): " +
               result.message,
           result.reason);
    return;
  }
  // The best point seen, which a line search may have found between rows.
  finish(FitProgress::State::finished, result.message, result.reason,
         std::make_shared<const FitOutcome>(fit_outcome(problem, *job.scene, result.best_theta)));
}

void FitWorker::run_online(FitProblem& problem, const FitJob& job) {
  OnlineAdaptation online(problem, job.online_settings);
  int windows = 0;
  while (!online.done()) {
    if (stop_.load()) {
      finish(FitProgress::State::finished, "stopped: kept the weights of the last window",
             std::nullopt);
      return;
    }
    const OnlineAdaptation::Update u = online.advance();
    ++windows;
    if (!std::isfinite(u.loss)) {
      finish(FitProgress::State::finished,
             "a window's loss was not finite (the cloth blew up): kept the weights before it",
             std::nullopt);
      return;
    }
    if (u.observed == 0) continue;
    publish_row(problem, *job.scene, online.theta(), u.loss, u.rms_m, windows, u.time);
  }
  finish(FitProgress::State::finished, "the reference ended", std::nullopt);
}

}  // namespace neurocloth
