#include "app/cli/long_run.h"

#include <tuple>

#include <chrono>
#include <csignal>
#include <cstdio>

namespace neurocloth {
namespace {

volatile std::sig_atomic_t g_interrupted = 0;

extern "C" void on_interrupt(int) {
  g_interrupted = 1;
}

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Called between frames: watches the clock (every few frames, which costs
// nothing beside a step) and the Ctrl-C flag.
class Progress {
 public:
  Progress(double start_time, double seconds, double every)
      : start_time_(start_time),
        seconds_(seconds),
        every_(every),
        start_(Clock::now()),
        next_(every) {}

  bool operator()(const Simulation& sim) {
    if (g_interrupted) return true;
    if (every_ <= 0 || ++frames_ % 16 != 0) return false;
    const double wall = since(start_);
    if (wall < next_) return false;
    const double done = sim.time() - start_time_;
    const double left = done > 0 ? wall * (seconds_ - done) / done : 0;
    if (!estimated_) {
      estimated_ = true;
      const long steps = sim.steps() + sim.rejected_steps() - first_steps_;
      std::fprintf(stderr,
                   "this run takes about %s in all (%.4g s simulated per wall second, %.3g us "
                   "per step); progress every %g s; Ctrl-C stops it and writes the state "
                   "reached\n",
                   human_duration(wall + left).c_str(), done / wall,
                   steps > 0 ? 1e6 * wall / static_cast<double>(steps) : 0.0, every_);
    }
    std::fprintf(stderr,
                 "progress: t = %.6g s of %.6g s (%.3g%%), %ld steps, %s wall, about %s left\n",
                 sim.time(), start_time_ + seconds_, 100 * done / seconds_, sim.steps(),
                 human_duration(wall).c_str(), human_duration(left).c_str());
    std::fflush(stderr);
    next_ = wall + every_;
    return false;
  }

  void begin(const Simulation& sim) { first_steps_ = sim.steps() + sim.rejected_steps(); }

 private:
  double start_time_, seconds_, every_;
  Clock::time_point start_;
  double next_;  // wall seconds of the next line: short runs print none
  long frames_ = 0, first_steps_ = 0;
  bool estimated_ = false;
};

}  // namespace

InterruptScope::InterruptScope() {
  g_interrupted = 0;
  struct sigaction action {};
  action.sa_handler = on_interrupt;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND;
  installed_ = sigaction(SIGINT, &action, &previous_) == 0;
}

InterruptScope::~InterruptScope() {
  if (installed_) sigaction(SIGINT, &previous_, nullptr);
}

bool InterruptScope::interrupted() {
  return g_interrupted != 0;
}

std::string human_duration(double s) {
  char buf[48];
  if (s < 90)
    std::snprintf(buf, sizeof buf, "%.2g s", s);
  else if (s < 5400)
    std::snprintf(buf, sizeof buf, "%.2g min", s / 60);
  else if (s < 172800)
    std::snprintf(buf, sizeof buf, "%.2g h", s / 3600);
  else if (s < 3.15e7 * 2)
    std::snprintf(buf, sizeof buf, "%.3g days", s / 86400);
  else
    std::snprintf(buf, sizeof buf, "%.3g years", s / 3.15576e7);
  return buf;
}

namespace {

// Runs `advance` under Ctrl-C and progress lines; what run_long and
// run_long_frames share.
template <class Advance>
LongRunOutcome run_watched(Simulation& sim, double seconds, const LongRunOptions& options,
                           Advance&& advance) {
  const InterruptScope scope;
  Progress progress(sim.time(), seconds, options.progress_every);
  progress.begin(sim);
  sim.set_interrupt([&](const Simulation& s) { return progress(s); });
  const Clock::time_point start = Clock::now();
  LongRunOutcome out;
  out.interrupted = advance(progress);
  out.wall_seconds = since(start);
  sim.set_interrupt({});
  return out;
}

}  // namespace

LongRunOutcome run_long(Simulation& sim, double seconds, const LongRunOptions& options) {
  return run_watched(sim, seconds, options, [&](Progress&) {
    sim.advance(seconds);
    return sim.interrupted();
  });
}

LongRunOutcome run_long_frames(Simulation& sim, double seconds, double fps,
                               const std::function<void(double, const ClothState&)>& frame,
                               const LongRunOptions& options) {
  const double start = sim.time(), end = start + seconds;
  long k = 1;  // the next frame: start + k / fps (no drift however many frames)
  ClothState before = sim.state(), between = sim.state();
  // After each accepted step from t0 over h: the frames inside it.
  auto stepped = [&](double t0, double h) {
    const ClothState& after = sim.state();
    for (;; ++k) {
      const double t = start + static_cast<double>(k) / fps;
      if (!(t <= end) || t > sim.time()) break;
      if (t == sim.time()) {
        frame(t, after);
        continue;
      }
      const double a = (t - t0) / h, b = 1.0 - a;
      for (auto [out, p, q] : {std::tuple{&between.x, &before.x, &after.x},
                               {&between.y, &before.y, &after.y},
                               {&between.z, &before.z, &after.z},
                               {&between.vx, &before.vx, &after.vx},
                               {&between.vy, &before.vy, &after.vy},
                               {&between.vz, &before.vz, &after.vz}})
        for (std::size_t i = 0; i < out->size(); ++i)
          (*out)[i] = b * (*p)[i] + a * (*q)[i];
      frame(t, between);
    }
    before = after;
  };
  const bool adaptive = sim.settings().adaptive;
  if (adaptive)
    sim.set_observer([&](const StepEvent& e) {
      if (e.accepted) stepped(e.time, e.step);
    });
  const LongRunOutcome out = run_watched(sim, seconds, options, [&](Progress& progress) {
    if (adaptive) {
      sim.advance(seconds);
      return sim.interrupted();
    }
    // Fixed steps one call each: advance(k dt) takes the same steps however it
    // is split (Simulation::advance).
    while (sim.time() < end) {
      const double t0 = sim.time();
      sim.advance(std::min(sim.settings().dt, end - t0));
      if (sim.status() != RunStatus::ok || sim.budget_exhausted()) return false;
      stepped(t0, sim.time() - t0);
      if (progress(sim)) return true;
    }
    return false;
  });
  sim.set_observer({});
  return out;
}

}  // namespace neurocloth
