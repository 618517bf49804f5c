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
//
// A module is part of the model: built once, then const. What a module keeps
// from step to step (self-collision's candidate pairs) lives in a ModuleState
// the simulation owns beside the cloth's state, so a copied simulation carries
// its own and two copies never share one. A live change of a parameter makes a
// new module (clone, then set): a copy of the model never sees it.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "core/network/cloth_state.h"
#include "core/network/force_context.h"
#include "core/network/force_inputs.h"
#include "core/network/parameter_id.h"

namespace neurocloth {

class ClothNetwork;

// What a constraint keeps between steps, and its scratch: part of the
// simulation's state, copied with it.
class ModuleState {
 public:
  virtual ~ModuleState() = default;
  virtual std::unique_ptr<ModuleState> clone() const = 0;
  virtual std::size_t bytes() const = 0;
  // True when `other` keeps the same bits between steps (scratch a step
  // rewrites before reading is not compared): a restored run must match.
  virtual bool same_bits(const ModuleState& other) const = 0;
};

// A ModuleState that is one copyable value.
template <class T>
class ModuleStateOf final : public ModuleState {
 public:
  T value;
  std::unique_ptr<ModuleState> clone() const override {
    return std::make_unique<ModuleStateOf>(*this);
  }
  std::size_t bytes() const override { return value.bytes(); }
  bool same_bits(const ModuleState& other) const override {
    const auto* o = dynamic_cast<const ModuleStateOf*>(&other);
    return o != nullptr && value.same_bits(o->value);
  }
};

// The value inside a state a module made with ModuleStateOf<T>.
template <class T>
T& state_value(ModuleState* state) {
  return static_cast<ModuleStateOf<T>*>(state)->value;
}

class SceneModule {
 public:
  virtual ~SceneModule() = default;
  // The scene file's "type" ("box", "wind", ...).
  virtual const char* type() const = 0;
  // Bytes of per-node or per-triangle data the module holds (for the test
  // that an undeclared module allocates nothing, and for the viewer).
  virtual std::size_t state_bytes() const { return 0; }
  // A live change of one declared number between steps (for wind, one axis of
  // its velocity): `id` names the module's parameter and axis (parameter_id.h).
  // Made on a fresh clone (see above). False when the module has no such
  // parameter; the caller checks the range.
  virtual bool set_parameter(const ParameterId& /*id*/, double /*value*/) { return false; }
  // The current value of a parameter set_parameter takes (only `parameter` and
  // `axis` are read); nullopt when the module has none such.
  virtual std::optional<double> parameter(const ParameterId& /*id*/) const { return std::nullopt; }
  // Learning (docs/learning.md): true when the module has a hand-written adjoint
  // (add_forces_adjoint / apply_adjoint), so a fit can differentiate through it.
  virtual bool has_adjoint() const { return false; }
  // The scene's declaration, as JSON text, for reports and the viewer.
  std::string declaration;
};

class ForceModule : public SceneModule {
 public:
  virtual std::shared_ptr<ForceModule> clone() const = 0;
  // True when the forces depend on ForceInputs::time (a gust): forces cached at
  // a state are then stale at the next step.
  virtual bool time_dependent() const { return false; }
  // The most kinetic plus spring energy the module can legitimately put into
  // the cloth (J), for the divergence check's budget; `size` is the cloth's
  // extent in m. Dissipative modules put in none.
  virtual double energy_bound(const ClothNetwork& /*net*/, double /*size*/) const { return 0; }
  // The largest omega^2 (1/s^2) the module's forces give a free node, as a
  // bound on its rows of M^-1 times the forces' Jacobian (Gershgorin): the
  // step bound adds it to the springs' (stability.h). 0 for a module whose
  // forces do not stiffen the cloth (drag, wind).
  virtual double stiffness_bound(const ClothNetwork& /*net*/) const { return 0; }
  // Adds the module's force on every node to `force` (N). Must not allocate.
  // `inputs` are the step's (its time); `context` how the evaluation runs (its
  // threads); `net` is the model this module is part of.
  virtual void add_forces(const ClothNetwork& net, const ForceInputs& inputs,
                          const ForceContext& context, const ClothState& state,
                          NodeVectors& force) const = 0;
  // The adjoint of add_forces (back-propagation through time): given
  // adj_force = dE/dF, adds dE/dp and dE/dv into `adj_state`, dE/d(1/m_i) into
  // adj_inverse_mass (per node; null when not wanted), and dE/d(parameter)
  // into params[module_slot(...)] (kModuleParameterSlots of them).
  virtual void add_forces_adjoint(const ClothNetwork& /*net*/, const ForceInputs& /*inputs*/,
                                  const ForceContext& /*context*/, const ClothState& /*state*/,
                                  const NodeVectors& /*adj_force*/, ClothState& /*adj_state*/,
                                  double* /*adj_inverse_mass*/, double* /*params*/) const {}
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
  // The step's team, or null: a module whose nodes are corrected each on its
  // own may split its sweep over it (for_node_parts), the same bits as without.
  StepThreads* threads = nullptr;
};

class ConstraintModule : public SceneModule {
 public:
  // Order in which constraints run after a step, lowest first: prescribed
  // motion, then strain limits, then contact with colliders, then
  // self-collision (contact has the last word on where a node may be).
  enum Phase { prescribe = 0, limit = 1, contact = 2, self_contact = 3 };
  virtual Phase phase() const = 0;
  // A fresh state for a cloth of this module's topology; null when the module
  // keeps nothing between steps.
  virtual std::unique_ptr<ModuleState> make_state() const { return nullptr; }
  // Corrects `after` (positions and velocities) given the state the step
  // started from; `state` is what make_state() made, carried by the caller.
  // Pinned nodes (free == 0) are moved only by prescribe modules.
  virtual void apply(const ClothNetwork& net, const StepSpan& span, const StepStart& before,
                     ClothState& after, ModuleState* state) const = 0;
  // The adjoint of apply: `uncorrected` is `after` as apply received it; on
  // entry `adj` is dE/d(corrected after), on return dE/d(uncorrected after).
  // dE/d(before positions) is added into adj_before, dE/d(node friction) into
  // adj_friction (per node; null when not wanted), dE/d(own parameters) into
  // params[module_slot(...)] and, for a module with a path, the path's own
  // after them (gradient_slots() in all). Only for modules whose has_adjoint()
  // is true.
  virtual void apply_adjoint(const ClothNetwork& /*net*/, const StepSpan& /*span*/,
                             const StepStart& /*before*/, const ClothState& /*uncorrected*/,
                             ClothState& /*adj*/, NodeVectors& /*adj_before*/,
                             double* /*adj_friction*/, double* /*params*/) const {}
  // How many doubles apply_adjoint's `params` holds: the module parameters'
  // slots, then what a path adds (pin_motion: 3 per keyframe).
  virtual std::size_t gradient_slots() const { return kModuleParameterSlots; }
};

}  // namespace neurocloth
