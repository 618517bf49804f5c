// The simulation thread's loop: take the queued commands, apply them, run one
// slice of simulated time (paced to the wall clock or flat out), publish a
// snapshot and the status; repeat. Nothing here waits for a reader: snapshots
// and status are handed over by swapping a pointer (snapshot_exchange.h).
#include "runtime/simulation_thread.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <variant>

#include "runtime/command_queue.h"
#include "runtime/live_scene.h"
#include "runtime/realtime_pacer.h"
#include "runtime/snapshot_exchange.h"

namespace neurocloth {

namespace {

using Clock = std::chrono::steady_clock;

// Wall time between published snapshots at most while running (a display refresh).
constexpr double kPublishInterval = 1.0 / 60.0;
// How often a paused or diverged thread wakes to refresh its rates when no command comes.
constexpr double kIdleWait = 0.1;
constexpr std::size_t kEnergySamples = 600;  // 10 s at 60 status refreshes per second
// Wall time one advance() call should take: long enough that its per-call cost
// (a finiteness scan of the state) is noise, short enough to stop on time.
constexpr double kChunkWall = 0.002;
// Behind the wall clock by this much, the pacer stops catching up.
constexpr double kMinLag = 0.1;
// Re-synced within this long (s), or slower than kSlowRatio over the last
// second: not keeping up.
constexpr double kBehindMemory = 1.0;
constexpr double kSlowRatio = 0.9;

bool finite_positions(const FrameSnapshot& f) {
  return std::all_of(f.position.begin(), f.position.end(),
                     [](float v) { return std::isfinite(v); });
}

}  // namespace

struct SimulationThread::Impl {
  Options options;
  LiveScene live;  // the simulation thread's alone once it runs
  CommandQueue queue;
  SnapshotExchange snapshots;

  // Published status and ranges: replaced whole under the mutex (a pointer swap),
  // copied by readers outside it.
  mutable std::mutex status_mutex;
  std::shared_ptr<const SimulationStatus> status;
  std::shared_ptr<const std::vector<ParameterRange>> ranges;

  // Bookkeeping of the simulation thread.
  Clock::time_point origin = Clock::now();
  RealtimePacer pacer;
  RateWindow rates;
  std::vector<double> energy;  // a ring of kEnergySamples
  std::size_t energy_next = 0;
  double energy_time = -1;  // simulated time of the last energy sample
  long applied = 0, refused = 0;
  std::string last_error;
  std::string notice;  // LiveScene::stability_notice() at the last status refresh
  long generation = -1;
  bool stepping = false;
  double last_status = -1e300;  // wall time of the last status refresh
  long chunk = 1;               // steps per advance() call, tuned to kChunkWall

  std::thread thread;

  Impl(Scene scene, Options o)
      : options(check(o)),
        live(std::move(scene), o.start_paused),
        pacer(std::max(kMinLag, 2 * o.max_frame_seconds)) {}

  static Options check(Options o) {
    if (!(o.max_frame_seconds > 0 && std::isfinite(o.max_frame_seconds)))
      throw std::invalid_argument("SimulationThread: max_frame_seconds must be > 0");
    return o;
  }

  double wall() const {
    if (options.clock) return options.clock();
    return std::chrono::duration<double>(Clock::now() - origin).count();
  }

  void start() {
    live.set_stop_check([this] { return queue.stopping(); });
    generation = live.generation();
    publish();
    publish_ranges();
    refresh_status(wall(), true);
    thread = std::thread([this] { run(); });
  }

  void run() {
    std::deque<SimCommand> batch;
    while (queue.take_all(batch)) {
      try {
        if (!batch.empty()) apply(batch);
        step_or_wait();
      } catch (const std::exception& e) {
        // Nothing a slice throws may end the thread (posters would wait forever):
        // stop stepping and say why.
        last_error = std::string("simulation stopped: ") + e.what();
        live.apply(SetPaused{true});
        refresh_status(wall(), true);
      }
    }
  }

  void apply(const std::deque<SimCommand>& batch) {
    for (const SimCommand& c : batch) {
      if (queue.stopping()) break;  // the rest is dropped, as a stop drops the queue
      std::string why = std::holds_alternative<Advance>(c) && !options.lockstep
                            ? "Advance: only in lockstep mode (this thread paces itself)"
                            : live.apply(c);
      ++applied;
      if (!why.empty()) {
        ++refused;
        last_error = std::move(why);
      }
    }
    if (live.generation() != generation) {  // a new run: time went back
      generation = live.generation();
      rates.clear();
      energy.clear();
      energy_next = 0;
      energy_time = -1;
      stepping = false;
    }
    // Show the effect before releasing wait_for_commands().
    try {
      publish();
      publish_ranges();
      refresh_status(wall(), true);
    } catch (...) {
      queue.mark_done(static_cast<long>(batch.size()));
      throw;
    }
    queue.mark_done(static_cast<long>(batch.size()));
  }

  void step_or_wait() {
    Simulation& sim = live.simulation();
    const double now = wall();
    // In lockstep only Advance commands move time (applied in order with the rest).
    if (options.lockstep || live.paused() || sim.status() != RunStatus::ok) {
      stepping = false;
      queue.wait_for_work(std::chrono::duration<double>(kIdleWait));
      refresh_status(wall(), false);
      return;
    }
    if (!stepping) {  // (re)starting: owe nothing for the time spent paused
      pacer.sync(now, sim.time());
      rates.clear();
      stepping = true;
    }
    const double dt = sim.settings().dt;
    const int max_steps =
        std::max(1, static_cast<int>(std::floor(options.max_frame_seconds / dt + 1e-9)));
    const int steps = options.realtime ? pacer.plan(now, sim.time(), dt, max_steps) : max_steps;
    // In real time, slices of about a display frame: stepping as soon as one dt
    // is owed would publish a snapshot per step. Until then sleep (a command wakes it).
    const int min_steps = std::min(
        max_steps, std::max(1, static_cast<int>(std::floor(kPublishInterval / dt + 1e-9))));
    if (steps < min_steps) {
      const double wait = std::min(min_steps * dt - pacer.owed(now, sim.time()), kPublishInterval);
      queue.wait_for_work(std::chrono::duration<double>(std::max(wait, 0.0)));
      return;
    }
    run_slice(steps, now + kPublishInterval);
    publish();
    const double after = wall();
    refresh_status(after, sim.status() != RunStatus::ok);
  }

  // Up to `steps` steps of dt, stopping early at `deadline` (wall) so a slow
  // scene still publishes at display rate; the pacer carries what is left.
  void run_slice(int steps, double deadline) {
    Simulation& sim = live.simulation();
    const double dt = sim.settings().dt;
    long left = steps;
    while (left > 0 && sim.status() == RunStatus::ok) {
      const long n = std::min(left, chunk);
      const double t0 = wall();
      sim.advance(static_cast<double>(n) * dt);  // bit-identical to n calls of advance(dt)
      const double t1 = wall();
      left -= n;
      if (t1 - t0 < 0.5 * kChunkWall)
        chunk = std::min(2 * chunk, 1L << 20);
      else if (t1 - t0 > 2 * kChunkWall)
        chunk = std::max(1L, chunk / 2);
      if (t1 >= deadline) break;
    }
  }

  // The state as it is now, checked in full first (finite, energy within its
  // budget: one energy evaluation per frame), so a cloth that began to explode
  // since the last periodic check is rolled back to its last good state rather
  // than drawn. If even that leaves something unfinite, the previous snapshot stays.
  void publish() {
    Simulation& sim = live.simulation();
    FrameSnapshot& f = snapshots.back();
    f.geometry = live.geometry();  // first: capture places its colliders
    sim.check_now();
    capture(sim, f);
    if (!finite_positions(f)) {
      sim.check_now();
      capture(sim, f);
      if (!finite_positions(f)) return;
    }
    f.forces = live.forces();
    snapshots.publish();
  }

  bool keeping_up(double now) const {
    if (options.lockstep || !options.realtime || !stepping) return true;
    if (now - pacer.last_resync() < kBehindMemory) return false;
    return !(rates.covered() >= 0.5 * kBehindMemory && rates.realtime_ratio() < kSlowRatio);
  }

  // Running, at most every kPublishInterval (module reports allocate); always
  // when `force` (commands applied, a divergence).
  void refresh_status(double now, bool force) {
    if (!force && now - last_status < 0.5 * kPublishInterval) return;
    last_status = now;
    auto s = std::make_shared<SimulationStatus>();
    live.describe(*s);
    rates.add(now, s->time, s->steps);
    s->steps_per_second = rates.steps_per_second();
    s->realtime_ratio = rates.realtime_ratio();
    s->keeping_up = keeping_up(now);
    s->commands_applied = applied;
    s->commands_refused = refused;
    // A stability notice is reported once in last_error when it appears (the
    // viewer shows last_error), and taken back when the step is sane again.
    s->stability_notice = live.stability_notice();
    if (s->stability_notice != notice) {
      if (!s->stability_notice.empty())
        last_error = s->stability_notice;
      else if (last_error == notice)
        last_error.clear();
      notice = s->stability_notice;
    }
    s->last_error = last_error;
    if (s->time != energy_time) {  // one sample per refresh that moved time
      energy_time = s->time;
      const double e = live.simulation().energy().total();
      if (energy.size() < kEnergySamples)
        energy.push_back(e);
      else
        energy[energy_next] = e;
      energy_next = (energy_next + 1) % kEnergySamples;
    }
    s->energy_history.reserve(energy.size());
    if (energy.size() == kEnergySamples)  // full ring: the oldest is next to be overwritten
      s->energy_history.assign(energy.begin() + energy_next, energy.end());
    s->energy_history.insert(
        s->energy_history.end(), energy.begin(),
        energy.begin() + (energy.size() == kEnergySamples ? energy_next : energy.size()));
    std::shared_ptr<const SimulationStatus> fresh = std::move(s);
    std::lock_guard<std::mutex> lock(status_mutex);
    status.swap(fresh);  // the previous status is freed after the unlock
  }

  // Only commands change the ranges (LoadScene, LoadRules).
  void publish_ranges() {
    auto fresh = std::make_shared<const std::vector<ParameterRange>>(live.ranges());
    std::lock_guard<std::mutex> lock(status_mutex);
    ranges.swap(fresh);
  }
};

SimulationThread::SimulationThread(Scene scene, Options options)
    : impl_(std::make_unique<Impl>(std::move(scene), options)) {
  impl_->start();
}

SimulationThread::~SimulationThread() {
  impl_->queue.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

void SimulationThread::post(SimCommand command) {
  impl_->queue.post(std::move(command));
}

std::shared_ptr<const FrameSnapshot> SimulationThread::latest() const {
  return impl_->snapshots.latest();
}

SimulationStatus SimulationThread::status() const {
  std::shared_ptr<const SimulationStatus> s;
  {
    std::lock_guard<std::mutex> lock(impl_->status_mutex);
    s = impl_->status;
  }
  return *s;
}

void SimulationThread::wait_for_commands() const {
  impl_->queue.wait_until_done();
}

bool SimulationThread::wait_for_commands(std::chrono::duration<double> timeout) const {
  return impl_->queue.wait_until_done_for(timeout);
}

std::vector<ParameterRange> SimulationThread::parameter_ranges() const {
  std::shared_ptr<const std::vector<ParameterRange>> r;
  {
    std::lock_guard<std::mutex> lock(impl_->status_mutex);
    r = impl_->ranges;
  }
  return *r;
}

}  // namespace neurocloth
