#pragma once
// The simulation on its own thread. It owns the Simulation; others talk to it
// only through commands (a queue) and read only what it publishes: the newest
// FrameSnapshot (from a small pool of buffers, snapshot_exchange.h: the reader
// takes the newest without ever blocking the simulation) and a SimulationStatus
// copy. It runs in real time when it can keep up, and when it cannot it says so
// (simulated seconds per wall second) instead of stalling anyone; or, in
// lockstep, only as far as Advance commands take it.
#include <chrono>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/frame_snapshot.h"
#include "core/scene/scene.h"
#include "runtime/sim_command.h"

namespace neurocloth {

// A parameter's valid range, for the UI (shown when a typed value is refused)
// and for the thread's own check.
struct ParameterRange {
  ParameterId id;    // as in SetParameter
  std::string name;  // the id as text, for lists and messages
  double min, max;
  std::string unit;
};
// For the scene's own rule base (Scene::FuzzySource::rules: not read again).
std::vector<ParameterRange> parameter_ranges(const Scene& scene);
const ParameterRange* find_range(const std::vector<ParameterRange>& ranges, const ParameterId& id);

struct SimulationStatus {
  std::string scene_name, scene_path;
  std::shared_ptr<const Scene> scene;  // as loaded (before any LoadRules), shared: no copy
  RunStatus run = RunStatus::ok;
  std::string divergence_reason;
  double time = 0;  // simulated s
  long steps = 0, rejected_steps = 0;
  double step_cap = 0;  // current t_c cap (adaptive) or dt, s
  long substeps = 1;    // a fixed dt above the stable step runs as this many substeps
  bool step_budget_exhausted = false;  // the last advance stopped at its step budget
  // One line while the step is not what was asked (substeps, budget, forward
  // Euler above its limit); also shown once in last_error when it appears.
  std::string stability_notice;
  double steps_per_second = 0;  // accepted steps per wall second, recent
  double realtime_ratio = 1;    // simulated s per wall s, recent (1 = keeping up)
  bool keeping_up = true;
  bool paused = false;
  long commands_applied = 0;  // every command taken from the queue, applied or refused
  long commands_refused = 0;
  std::string last_error;  // the last refused command or failed load (one line)
  IntegratorKind integrator = IntegratorKind::network;
  bool adaptive = false;
  double dt = 0, viscosity = 0, friction = 0;
  Vec3 gravity = Vec3(0, -9.81, 0);
  std::optional<Vec3> wind;                                     // when the scene has a wind module
  std::vector<std::pair<std::string, double>> material_inputs;  // linguistic, when fuzzy
  std::vector<double> energy_history;  // total energy, recent samples (oldest first)
  std::vector<ModuleReport> modules;
};

class SimulationThread {
 public:
  struct Options {
    bool realtime = true;             // pace to the wall clock (false: as fast as it can)
    double max_frame_seconds = 0.05;  // simulated time per slice at most, before publishing
    bool start_paused = false;
    // Time moves only when told: the thread never steps on its own, each
    // Advance command moves simulated time on (docs/threads.md, "Lockstep").
    // For the window's --lockstep, tests and soak runs: a run is then the same
    // on a fast machine and a loaded one. `realtime` is ignored.
    bool lockstep = false;
    // Wall seconds from any fixed origin, read by the simulation thread (it
    // must be safe to call from there); empty: std::chrono::steady_clock. A
    // test hands in a clock it moves itself, so the real-time pacing can be
    // checked without depending on how fast the machine is.
    std::function<double()> clock;
  };
  explicit SimulationThread(Scene scene, Options options);
  explicit SimulationThread(Scene scene) : SimulationThread(std::move(scene), Options{}) {}
  // Stops and joins: the command being applied ends first (an Advance is cut
  // short between frames), the rest of the queue is dropped.
  ~SimulationThread();
  SimulationThread(const SimulationThread&) = delete;
  SimulationThread& operator=(const SimulationThread&) = delete;

  void post(SimCommand command);  // thread-safe, never waits for a step
  // The newest published snapshot (never null after construction); never blocks the simulation.
  std::shared_ptr<const FrameSnapshot> latest() const;
  SimulationStatus status() const;
  // Blocks until every command posted so far has been taken (for tests and scripts).
  // Taken means applied (or refused): status() and latest() then show its effect.
  void wait_for_commands() const;
  // The same for at most `timeout`: false when some were still pending then
  // (a soak or script that must not wait forever on a costly command).
  bool wait_for_commands(std::chrono::duration<double> timeout) const;
  // The ranges SetParameter checks against for the scene running now (they
  // change with LoadScene and LoadRules); like status(), a copy.
  std::vector<ParameterRange> parameter_ranges() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace neurocloth
