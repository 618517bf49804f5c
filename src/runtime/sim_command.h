#pragma once
// What the UI (or a script, or a test) may ask of the simulation thread. The
// UI never writes simulation state: it posts one of these and the simulation
// thread applies it between steps.
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "core/base/vec3.h"
#include "core/integrators/integrator.h"
#include "core/network/material.h"
#include "core/network/parameter_id.h"
#include "core/scene/fuzzy_material.h"
#include "core/simulation/solver_settings.h"

namespace neurocloth {

struct Scene;

// One number (parameter_id.h says which there are), checked against
// parameter_ranges(). A linguistic input is ramped in; the others take effect
// at the next step.
struct SetParameter {
  ParameterId id;  // parsed against the running scene's ParameterNames
  double value;
};
struct SetIntegrator {
  IntegratorKind kind;
};
struct SetAdaptive {
  bool on;
};
// The solver as a whole, in one step (the Solver panel's accuracy slider picks
// all of these together; applied one by one an intermediate mix could be
// unstable). The run's own guards (step budget, substeps) are kept.
struct SetSolver {
  IntegratorKind integrator;
  double dt;       // s: the fixed step, or the refresh interval when adaptive
  bool adaptive;   // the paper's propagation (network integrator)
  double safety;   // adaptive: t_c <= safety * stable step bound
  int iterations;  // projective: local-global iterations per step; vbd: sweeps (the others ignore
                   // it)
  // implicit_euler: its conjugate gradient's relative residual (ignored by the others)
  double linear_tolerance;
};
// The command that asks for `s` as a whole: the one place solver settings
// become a SetSolver (the accuracy slider's pick, the scene's own solver back).
inline SetSolver solver_command(const SolverSettings& s) {
  return SetSolver{s.integrator,      s.dt, s.adaptive, s.adaptive_settings.safety, s.iterations,
                   s.linear_tolerance};
}
// Pulls node `node` with `force` (N) towards `anchor` (drawn as a line) until released.
struct ApplyForce {
  int node;
  Vec3 force;
  Vec3 anchor;
};
struct ReleaseForce {
  int node;
};
struct SetPinned {
  int node;
  bool pinned;
};
struct SetPaused {
  bool paused;
};
struct SingleStep {};  // one refresh interval (dt) while paused
// The lockstep clock (SimulationThread::Options::lockstep, the window's
// --lockstep): simulated time moves on by `seconds` unless paused, in whole
// steps of dt with the remainder carried to the next Advance, so a run depends
// on the commands alone, never on how fast the machine is. Refused when the
// thread paces itself, and outside [0, 1] s (one Advance holds the queue).
struct Advance {
  double seconds;
};
struct Reset {};  // the scene's initial state and parameters
struct LoadScene {
  std::string path;  // on failure the running scene keeps going; the error is reported
  // The scene read from `path` by whoever sends this (the UI reads it to check
  // it): the thread takes it as it is. Null: the thread reads `path`.
  std::shared_ptr<const Scene> scene = nullptr;
};
struct LoadRules {
  std::string path;  // an FCL rule base for the current linguistic material
  // The rule base read from `path` by whoever sends this (the UI reads it to
  // show it): the thread takes it as it is. Null: the thread reads `path`.
  std::shared_ptr<const FuzzyMaterial> rules = nullptr;
};

// A fitted material, and fitted module parameters, for the running cloth (the
// window's Learning panel): the weights ramp to the material over 64 steps, as
// for a linguistic input, so the cloth takes it without a jolt. The fit's
// viscosity and friction replace the user's. Refused whole (nothing changes)
// when a value is not finite or outside the scene limits, or a module
// parameter cannot change live (a collider's friction).
struct ApplyFit {
  Material material;
  // Module ids as the running scene's ParameterNames index them.
  std::vector<std::pair<ParameterId, double>> module_parameters;
  // A fit of a material's inputs (input.NAME ids): the rule base derives the
  // material from them, and `material` is not applied.
  std::vector<std::pair<ParameterId, double>> inputs;
};

using SimCommand =
    std::variant<SetParameter, SetIntegrator, SetAdaptive, SetSolver, ApplyForce, ReleaseForce,
                 SetPinned, SetPaused, SingleStep, Advance, Reset, LoadScene, LoadRules, ApplyFit>;

}  // namespace neurocloth
