#pragma once
// A fit to a reference motion on its own thread, beside the simulation thread
// and the window: the window's Learning panel starts one, polls its progress
// each frame, stops it, and applies what it found to the running cloth
// (ApplyFit, sim_command.h). The worker fits its own copy of the scene as it
// was loaded, never the running one, so the cloth keeps running meanwhile.
//
// Threads: start(), stop() and progress() may be called from any thread. The
// worker writes the progress under a mutex, whole, after every iteration (or
// online window); readers copy it. Stop sets an atomic flag the optimiser
// reads before every evaluation (OptimizerOptions::should_stop), so a stop
// lands within one evaluation of the loss.
#include <atomic>
#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "core/scene/scene.h"
#include "learn/fit/fit_problem.h"
#include "learn/fit/online_adaptation.h"
#include "learn/motion/reference_motion.h"
#include "learn/optim/optimizer.h"
#include "runtime/sim_command.h"

namespace neurocloth {

struct FitJob {
  std::shared_ptr<const Scene> scene;  // as loaded: the fit starts from its initial state
  std::shared_ptr<const ReferenceMotion> reference;
  FitSettings settings;  // params, per element, tape budget
  OptimizerMethod method = OptimizerMethod::lbfgs;
  int max_iterations = 50;
  // Online adaptation (online_adaptation.h) through the reference once,
  // instead of the batch fit.
  bool online = false;
  OnlineSettings online_settings;
};

// What a fit found, as the running cloth takes it.
struct FitOutcome {
  ApplyFit command;  // the fitted material and the fitted force-module parameters
  // Fitted blocks the live cloth cannot take, with why ("rest_length: ...").
  std::vector<std::string> not_applied;
  // A fit of a material's inputs, in the rule base's words (fit_problem.h).
  std::vector<std::string> words;
};

struct FitProgress {
  enum class State { idle, running, finished, failed };
  State state = State::idle;
  long job = 0;     // the start() this belongs to (1, 2, ...)
  long serial = 0;  // increases with every change
  bool online = false;
  // One column per block of theta: its name, unit, and its value's history
  // (per iteration; online, per window that observed something).
  std::vector<std::string> names, units;
  std::vector<std::vector<double>> values;
  std::vector<double> loss;   // m^2, the same rows
  std::vector<double> rms_m;  // RMS node distance, m
  int iteration = 0;          // the last recorded (online: windows advanced)
  double online_time = 0;     // online: the last window's end, s
  double duration = 0;        // the reference's, s
  // Why it ended (finished) or failed (the scene cannot be fitted: one line).
  std::string message;
  std::optional<StopReason> reason;  // batch fits
  // The parameters of the newest row (null before the first): what Apply sends.
  std::shared_ptr<const FitOutcome> outcome;
};
const char* to_string(FitProgress::State state);

class FitWorker {
 public:
  // `on_row` (tests) is called on the worker thread after every published
  // row, with the row's index: a test may stop the fit there, deterministically.
  explicit FitWorker(std::function<void(int row)> on_row = {});
  ~FitWorker();  // stops the fit and joins
  FitWorker(const FitWorker&) = delete;
  FitWorker& operator=(const FitWorker&) = delete;

  // Starts `job` on a new worker thread; "" when started, else why not (one
  // is running, no scene or reference). A scene that cannot be fitted ends the
  // job as failed, with the reason in progress().message.
  std::string start(FitJob job);
  // Asks the running fit to stop (it keeps the best parameters found). Any thread.
  void stop();
  bool running() const;
  // A copy of the progress; cheap to skip when serial() has not moved.
  FitProgress progress() const;
  long serial() const { return serial_.load(std::memory_order_acquire); }
  // Blocks until no fit is running (tests, scripts).
  void wait() const;

 private:
  void run(FitJob job);
  void run_batch(FitProblem& problem, const FitJob& job);
  void run_online(FitProblem& problem, const FitJob& job);
  // Appends a row and publishes it, then calls on_row_.
  void publish_row(FitProblem& problem, const Scene& scene, const Eigen::VectorXd& theta,
                   double loss, double rms, int iteration, double online_time);
  void finish(FitProgress::State state, std::string message, std::optional<StopReason> reason,
              std::shared_ptr<const FitOutcome> outcome = nullptr);
  template <class Change>
  void update(Change&& change);

  std::function<void(int)> on_row_;
  mutable std::mutex mutex_;  // guards progress_ and running_
  mutable std::condition_variable done_;
  FitProgress progress_;
  bool running_ = false;
  std::atomic<long> serial_{0};
  std::atomic<bool> stop_{false};
  long jobs_ = 0;
  std::thread thread_;
};

// The outcome of `theta` for the running cloth: the fitted material and the
// fitted module parameters as ids of `scene`'s names.
FitOutcome fit_outcome(const FitProblem& problem, const Scene& scene, const Eigen::VectorXd& theta);

}  // namespace neurocloth
