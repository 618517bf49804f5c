#pragma once
// Scene modules: the effects a scene declares (colliders, air, strain limits,
// self-collision, pin motion) on top of the bare network. A scene builds its
// list of modules once; the step then runs exactly that list, so a module not
// declared costs nothing and no hot loop tests a flag.
//
// Two kinds, by where they act:
//  - a ForceModule adds forces inside every force evaluation (the acceleration
//    neurons' bias input), so every integrator, RK4 stage and implicit solve
//    sees it;
//  - a ConstraintModule corrects the state after each integrator step (a
//    projection: contact, strain limits, prescribed pin positions).
#include <chrono>
#include <cstddef>
#include <string>

#include "../cloth_state.h"
#include "../parameter_id.h"

namespace neurocloth {

class ClothNetwork;

// Wall time a module has spent, for RESULT.json and the viewer.
struct ModuleClock {
  double seconds = 0;
  long calls = 0;
};

// Times one call into `clock` (two steady_clock reads: tens of ns per call).
class ScopedModuleTimer {
 public:
  explicit ScopedModuleTimer(ModuleClock& c)
      : clock_(c), start_(std::chrono::steady_clock::now()) {}
  ~ScopedModuleTimer() {
    clock_.seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    ++clock_.calls;
  }
  ScopedModuleTimer(const ScopedModuleTimer&) = delete;
  ScopedModuleTimer& operator=(const ScopedModuleTimer&) = delete;

 private:
  ModuleClock& clock_;
  std::chrono::steady_clock::time_point start_;
};

class SceneModule {
 public:
  virtual ~SceneModule() = default;
  // The scene file's "type" ("box", "wind", ...).
  virtual const char* type() const = 0;
  // Bytes of per-node or per-triangle state the module holds (for the test
  // that an undeclared module allocates nothing, and for the viewer).
  virtual std::size_t state_bytes() const { return 0; }
  // A live change of one declared number between steps (for wind, one axis of
  // its velocity): `id` names the module's parameter and axis (parameter_id.h).
  // False when the module has no such parameter; the caller checks the range
  // and drops cached forces (Simulation::mutable_network).
  virtual bool set_parameter(const ParameterId& /*id*/, double /*value*/) { return false; }
  // The scene's declaration, as JSON text, for reports and the viewer.
  std::string declaration;
  mutable ModuleClock clock;
};

class ForceModule : public SceneModule {
 public:
  // Once per step, before it: time-dependent inputs (a gust) are frozen for the
  // step. Returns true when the forces at a given state changed (cached forces
  // are then recomputed).
  virtual bool begin_step(double /*time*/) { return false; }
  // The most kinetic plus spring energy the module can legitimately put into
  // the cloth (J), for the divergence check's budget; `size` is the cloth's
  // extent in m. Dissipative modules put in none.
  virtual double energy_bound(const ClothNetwork& /*net*/, double /*size*/) const { return 0; }
  // Adds the module's force on every node to `force` (N). Must not allocate.
  virtual void add_forces(const ClothNetwork& net, const ClothState& state,
                          NodeVectors& force) const = 0;
};

// Where the nodes were when the step began (positions only: no constraint
// needs more, and a step taken in place then needs to keep only these).
struct StepStart {
  const double* x;
  const double* y;
  const double* z;
  std::size_t n;
  StepStart(const ClothState& s) : x(s.x.data()), y(s.y.data()), z(s.z.data()), n(s.size()) {}
  StepStart(const NodeVectors& p) : x(p.x.data()), y(p.y.data()), z(p.z.data()), n(p.size()) {}
  Vec3 position(std::size_t i) const { return {x[i], y[i], z[i]}; }
  std::size_t size() const { return n; }
};

// The step a constraint corrects: from `before` at time t0 to `after` at t0 + h.
struct StepSpan {
  double t0;
  double h;
};

class ConstraintModule : public SceneModule {
 public:
  // Order in which constraints run after a step, lowest first: prescribed
  // motion, then strain limits, then contact with colliders, then
  // self-collision (contact has the last word on where a node may be).
  enum Phase { prescribe = 0, limit = 1, contact = 2, self_contact = 3 };
  virtual Phase phase() const = 0;
  // Corrects `after` (positions and velocities) given the state the step
  // started from. Pinned nodes (free == 0) are moved only by prescribe modules.
  virtual void apply(const ClothNetwork& net, const StepSpan& span, const StepStart& before,
                     ClothState& after) = 0;
};

}  // namespace neurocloth
