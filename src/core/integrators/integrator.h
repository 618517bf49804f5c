#pragma once
// Every integrator steps the same network: it reads the neurons' outputs
// (ClothState), asks the network for forces, and writes the next state. None of
// them owns the network or allocates during a step.
#include <memory>
#include <optional>
#include <string>

#include "core/integrators/step_controller.h"
#include "core/network/cloth_network.h"

namespace neurocloth {

enum class IntegratorKind { network, explicit_euler, verlet, rk4, implicit_euler, projective, vbd };
inline constexpr IntegratorKind kAllIntegrators[] = {
    IntegratorKind::network, IntegratorKind::explicit_euler, IntegratorKind::verlet,
    IntegratorKind::rk4,     IntegratorKind::implicit_euler, IntegratorKind::projective,
    IntegratorKind::vbd};

// The large steps that minimise backward Euler's energy by a fixed number of
// iterations a step (their accuracy knob, SolverSettings::iterations) and take
// fixed steps: projective (local-global) and vbd (vertex block descent).
inline bool iterates_per_step(IntegratorKind k) {
  return k == IntegratorKind::projective || k == IntegratorKind::vbd;
}

// Iterations per step of `projective` and `vbd` (their accuracy knob) unless a scene says.
inline constexpr int kDefaultProjectiveIterations = 10;
// The implicit step's conjugate gradient stops at |r| <= this * |b|. Tight
// enough that the linear solve adds nothing visible to the step's own error
// (docs/network.md, "Large steps").
inline constexpr double kDefaultLinearTolerance = 1e-10;

// What preconditions the implicit step's conjugate gradient (docs/network.md,
// "The implicit step's preconditioner"). automatic: the Laplacian from
// kMinLaplacianNodes nodes, Jacobi below. laplacian: the large steps'
// prefactored matrix M + h^2 L (spring_laplacian.h) between two block-Jacobi
// sweeps. multigrid: the algebraic multigrid of the step's own matrix (Jacobi
// below its own size limits). jacobi: the diagonal. The step is backward Euler to
// the CG tolerance whichever it is; only its cost and last bits differ.
enum class ImplicitPreconditioner { automatic, laplacian, multigrid, jacobi };
inline constexpr const char* kImplicitPreconditionerNames = "auto, laplacian, multigrid, jacobi";

const char* to_string(IntegratorKind k);
std::optional<IntegratorKind> parse_integrator(const std::string& name);
// "network, explicit_euler, ..." for error messages.
std::string integrator_names();

struct StepReport {
  int force_evaluations = 0;  // including the start-of-step evaluation
  int cg_iterations = 0;      // or projective's local-global iterations, vbd's sweeps
  bool cg_converged = true;
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual IntegratorKind kind() const = 0;
  // An independent copy (scratch included), for copying a simulation.
  virtual std::unique_ptr<Integrator> clone() const = 0;
  // Global order of accuracy.
  virtual int order() const = 0;
  // Largest h * omega for which an undamped linear oscillator stays bounded
  // (infinity when unconditionally stable). The adaptive step scales its bound by it.
  virtual double stability_limit() const = 0;
  // Advances `in` by h into `out` (which must not alias `in` unless steps_in_place()).
  // `start_force` is net_forces(in, inputs, context) (stale when
  // reads_start_force() is false): the caller has it for the adaptive rule, the
  // step its FSAL cache. Every force evaluation of the step reads the same
  // `inputs`, and its sweeps split over context.threads.
  virtual StepReport step(const ClothNetwork& net, const ForceInputs& inputs,
                          const ForceContext& context, const ClothState& in,
                          const NodeVectors& start_force, double h, ClothState& out) = 0;
  // True when `out` may be the same object as `in`: a fixed step then touches
  // one state buffer instead of two (half the memory traffic on large cloths).
  virtual bool steps_in_place() const { return false; }
  // False when step() never reads `start_force` (its forces come from its own
  // sweeps): a fixed step then passes stale forces instead of paying a sweep
  // over every spring for them.
  virtual bool reads_start_force() const { return true; }
  // True when the step damps the springs itself (damp_springs) and its forces
  // come without the damping term (ForceContext::spring_damping false): its
  // stability bound is then the springs' stiffness alone.
  virtual bool damps_springs() const { return false; }
};

// Scratch is sized for `net`; the integrator may then step any network of that size.
// `min_step_fraction` is the floor of the implicit step's pieces (step_controller.h);
// `iterations` the projective step's local-global iterations or vbd's sweeps; `linear_tolerance`
// the implicit step's conjugate gradient tolerance (relative residual) and
// `preconditioner` what preconditions it; `implicit_damping` the network
// step's damping taken spring by spring (spring_damping.h; the other
// integrators refuse it).
std::unique_ptr<Integrator> make_integrator(
    IntegratorKind kind, const ClothNetwork& net,
    double min_step_fraction = kDefaultMinStepFraction,
    int iterations = kDefaultProjectiveIterations,
    double linear_tolerance = kDefaultLinearTolerance,
    ImplicitPreconditioner preconditioner = ImplicitPreconditioner::automatic,
    bool implicit_damping = false);

}  // namespace neurocloth
