#pragma once
// The scene the simulation thread runs, and what the user has changed about it
// since it was loaded. Only the simulation thread touches it; every command is
// checked here, and a refused command leaves everything as it was.
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/scene/frame_snapshot.h"
#include "core/scene/fuzzy_material.h"
#include "core/scene/scene.h"
#include "runtime/sim_command.h"
#include "runtime/simulation_thread.h"

namespace neurocloth {

// "[0, 100] N s/m", for messages.
std::string describe_range(const ParameterRange& range);

class LiveScene {
 public:
  // The scene's rule base is the one it was loaded with (never read again).
  explicit LiveScene(Scene scene, bool paused = false);
  ~LiveScene();
  LiveScene(const LiveScene&) = delete;
  LiveScene& operator=(const LiveScene&) = delete;

  // Applies one command between steps: "" when done, else one line saying why
  // it was refused (nothing changed then).
  std::string apply(const SimCommand& command);

  Simulation& simulation();
  const Simulation& simulation() const;
  const Scene& scene() const;
  bool paused() const { return paused_; }
  // Increases whenever the run restarts (Reset, LoadScene): time went back.
  long generation() const { return generation_; }
  const std::vector<ParameterRange>& ranges() const;
  // What input and module ids index in the running scene.
  const ParameterNames& names() const;
  const std::shared_ptr<const SceneGeometry>& geometry() const;
  const std::vector<FrameSnapshot::AppliedForce>& forces() const { return forces_; }

  // Fills the status fields that describe the run and its parameters (those
  // read from the network show what it really uses, mid-ramp included).
  void describe(SimulationStatus& status);

  // One line when the step is not what the user asked for, else "": a fixed
  // dt above the stable step taken in substeps (the guard: live runs set
  // SolverSettings::substep_above_cap), a step budget that ran out in the last
  // advance (time falls behind), or forward Euler above its damped limit
  // (it gains energy: a divergence is coming). docs/stability.md.
  std::string stability_notice();

  // Asked between the frames of an Advance: true cuts it short (the thread is
  // stopping; an Advance at the step's floor can otherwise hold it for minutes).
  void set_stop_check(std::function<bool()> stop) { stop_ = std::move(stop); }

 private:
  struct Run;  // a scene with everything built from it, replaced as a whole

  std::string on(const SetParameter& c);
  std::string on(const SetIntegrator& c);
  std::string on(const SetAdaptive& c);
  std::string on(const SetSolver& c);
  std::string on(const ApplyForce& c);
  std::string on(const ReleaseForce& c);
  std::string on(const SetPinned& c);
  std::string on(const SetPaused& c);
  std::string on(const SingleStep& c);
  std::string on(const Advance& c);
  std::string on(const Reset& c);
  std::string on(const LoadScene& c);
  std::string on(const LoadRules& c);
  std::string on(const ApplyFit& c);

  void set_parameter(const ParameterId& id, double value);
  // "" when `node` is a node of the cloth, else why not.
  std::string check_node(const char* command, int node) const;
  // The material the network should settle on: the rule base's for `inputs`
  // (or the scene's own), with the user's viscosity and friction.
  Material target_material(const std::map<std::string, double>& inputs) const;
  Material target_material() const { return target_material(inputs_); }
  // Starts `run` with the scene's own parameters and no user changes.
  void start(std::unique_ptr<Run> run);

  std::unique_ptr<Run> run_;
  // What the user changed (cleared by Reset and LoadScene).
  std::optional<double> viscosity_, friction_;
  // A fitted material applied (ApplyFit): what the network settles on instead
  // of the scene's or the rule base's, until an input changes or the run restarts.
  std::optional<Material> fitted_;
  std::map<std::string, double> inputs_;  // linguistic inputs, fuzzy scenes only
  std::optional<Vec3> wind_;              // the mean wind, scenes with wind only
  std::vector<FrameSnapshot::AppliedForce> forces_;
  bool paused_;
  long generation_ = 0;
  // Advance: simulated seconds asked for but not yet stepped (less than one dt
  // after each Advance). Nothing is owed for a pause or across a restart.
  double owed_ = 0;
  std::function<bool()> stop_;
};

}  // namespace neurocloth
