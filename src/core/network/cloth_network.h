#pragma once
// The cloth as the paper's recurrent network: a spring layer feeding a mass
// layer, whose position and velocity neurons feed back into the spring layer.
// The network is the model: every parameter a user sets or learning adapts
// (weights, rest lengths, masses, gravity, the force modules). What changes
// from step to step is not in it: the neuron outputs live in ClothState, the
// other inputs of the acceleration neurons (external forces, the clock) in
// ForceInputs, how an evaluation runs (threads, arithmetic, clocks) in
// ForceContext, scratch activations in SpringActivations. So a const network
// can be evaluated on any state (RK4 stages, learning, rollback), and copies of
// it are independent.
#include <memory>
#include <vector>

#include "core/network/cloth_state.h"
#include "core/network/cloth_topology.h"
#include "core/network/force_context.h"
#include "core/network/force_inputs.h"
#include "core/network/mass_layer.h"
#include "core/network/material.h"
#include "core/network/scene_module.h"
#include "core/network/spring_kernel.h"
#include "core/network/spring_layer.h"

namespace neurocloth {

// Outputs of the force neurons, one 3-vector per spring: the force on n_i1
// (the force on n_i2 is its negative). The step itself does not keep them (see
// net_forces); spring_outputs() fills this for whoever wants to look.
struct SpringActivations {
  std::vector<double> fx, fy, fz;
  void resize(std::size_t springs) {
    for (auto* a : {&fx, &fy, &fz})
      a->assign(springs, 0.0);
  }
};

// The weights a material sets: one per spring (stiffness, damping) and per node
// (inverse mass, friction), in the network's order.
struct MaterialWeights {
  std::vector<double> stiffness, damping, inverse_mass, friction;
};

// Below this length a spring has no direction; its force is skipped, never divided by.
inline constexpr double kMinSpringLength = 1e-12;

struct Energy {
  double kinetic = 0;
  double spring = 0;
  double gravity = 0;  // -sum m g.p over free nodes
  double potential() const { return spring + gravity; }
  double total() const { return kinetic + spring + gravity; }
};

class ClothNetwork {
 public:
  SpringLayer springs;
  MassLayer masses;
  Vec3 gravity = Vec3(0, -9.81, 0);
  // Per node, how many of a material's node masses it carries (1 unless the
  // scene says otherwise): apply_material() sets m_i = node_mass * mass_share_i.
  // Cold data, read only when a material is applied.
  std::vector<double> mass_share;
  // Per spring, how many of a material's spring constants and viscosities it
  // carries (1 each unless the scene says otherwise: a measured material on a
  // mesh, measured_material.h). Cold data like mass_share.
  std::vector<double> spring_share;
  // The scene's force modules (air drag, wind): more inputs to the acceleration
  // neurons, evaluated with the springs. Empty unless the scene declares them.
  // Immutable, so copies of the network share them safely; a live change
  // replaces one (Simulation::set_module_parameter).
  std::vector<std::shared_ptr<const ForceModule>> force_modules;

  // Builds the layers from a topology: one spring per SpringSpec (rest length from
  // the rest positions), the material's constants as initial weights, each
  // node weighing mass_share (one per node; empty: 1 each) node masses.
  static ClothNetwork build(const ClothTopology& topology, const Material& material,
                            const SpringFunction& function = {},
                            std::vector<double> mass_share = {},
                            std::vector<double> spring_share = {});

  std::size_t node_count() const { return masses.size(); }
  std::size_t spring_count() const { return springs.size(); }
  double mass(std::size_t node) const { return 1.0 / masses.inverse_mass[node]; }
  void set_pinned(std::size_t node, bool pinned) { masses.free[node] = pinned ? 0.0 : 1.0; }
  // The weights `material` gives this network's springs and nodes.
  MaterialWeights material_weights(const Material& material) const;
  // Re-applies a material's constants to every spring and node (all weights).
  void apply_material(const Material& material);
  void set_weights(const MaterialWeights& weights);

  // Propagates the spring layer and sums its outputs into the acceleration
  // neurons: F_j = sum_i w_ij f_i + f_ext,j (weights +-1), plus whatever the
  // force modules add. Allocates nothing.
  // A spring shorter than kMinSpringLength contributes no force (no direction).
  // The springs' sweep is split over context.threads when it is set (the same
  // bits as on one thread, step_threads.h). Throws std::invalid_argument, before
  // any work, when the CPU cannot run context.kernel (spring_kernel.h).
  void net_forces(const ClothState& state, const ForceInputs& inputs, const ForceContext& context,
                  NodeVectors& force) const;
  // The same with no external force, at time 0, in a default context.
  void net_forces(const ClothState& state, NodeVectors& force) const;
  // Everything net_forces adds except the spring layer: the external force and
  // the force modules (what a large-step solver treats as given over a step).
  void other_forces(const ClothState& state, const ForceInputs& inputs, const ForceContext& context,
                    NodeVectors& force) const;
  // How many springs are that short at `state` (a diagnostic, off the hot path).
  int degenerate_springs(const ClothState& state) const;
  // The force neurons' outputs themselves, one per spring (for inspection and
  // learning), in the arithmetic net_forces uses at `precision`, by `kernel`.
  void spring_outputs(const ClothState& state, SpringActivations& act,
                      SpringPrecision precision = SpringPrecision::float64,
                      SpringKernel kernel = SpringKernel::automatic) const;
  // a_j = free_j * (F_j / m_j + g): what the velocity neuron integrates.
  void accelerations(const NodeVectors& force, NodeVectors& acc) const;
  // Largest |F_j + m_j g| over free nodes: the paper's "max sum f_i" (Table 1);
  // NaN when any is. The parts of `threads` (when given) share the scan.
  double max_net_force(const NodeVectors& force, StepThreads* threads = nullptr) const;

  Energy energy(const ClothState& state) const;
  // The external forces' potential, -sum f_j . p_j over free nodes (J).
  double external_potential(const ClothState& state, const ForceInputs& inputs) const;
  // The state at rest: nodes at `positions`, velocities zero.
  ClothState rest_state(const std::vector<Vec3>& positions) const;

 private:
  void external_force(const ForceInputs& inputs, NodeVectors& force, std::size_t lo,
                      std::size_t hi) const;
  void add_module_forces(const ClothState& state, const ForceInputs& inputs,
                         const ForceContext& context, NodeVectors& force) const;
};

}  // namespace neurocloth
