#pragma once
// How a scene asks to be propagated. Defaults are documented in docs/scenes.md;
// the step budget and the stable-substep guard in docs/stability.md.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/base/step_threads.h"
#include "core/integrators/integrator.h"
#include "core/integrators/spring_damping.h"
#include "core/integrators/stability.h"
#include "core/integrators/step_controller.h"
#include "core/io/physical_limits.h"
#include "core/network/spring_kernel.h"
#include "core/network/spring_precision.h"

namespace neurocloth {

// The paper's Table 1 plus what it lacks (see docs/network.md, "Adaptive step").
struct AdaptiveSettings {
  double safety = 0.5;  // t_c never exceeds safety * stable_step_bound
  // "The force grows" means max|F| > former + growth_tolerance * max(former, weight scale).
  double growth_tolerance = 0.05;
  // The one floor on a trial step, as a fraction of its cap (step_controller.h):
  // the adaptive t_c and the implicit step's pieces.
  double min_step_fraction = kDefaultMinStepFraction;
};

struct DivergenceSettings {
  int check_interval = 64;      // accepted steps between checks (and checkpoints)
  double runaway_factor = 1e4;  // energy above factor * budget is a strike
  int runaway_checks = 2;       // consecutive strikes that make a divergence
  double hard_factor = 1e10;    // above this, one strike is enough
  // The mechanical energy may rise over the last good state's by this many
  // budgets, plus this fraction of the kinetic + spring energy it holds (an
  // integrator's error is relative: forward Euler's free fall gains 1/64 of
  // its kinetic energy over its first 64 steps), between checks
  // (divergence_monitor.h; measured in docs/stability.md).
  double growth_factor = 1.0;
  double growth_fraction = 0.1;
};

struct SolverSettings {
  IntegratorKind integrator = IntegratorKind::network;
  double dt = 1e-3;  // fixed step, or the refresh interval t_delta when adaptive
  bool adaptive = false;
  AdaptiveSettings adaptive_settings;
  DivergenceSettings divergence;
  // The most trial steps (accepted, rejected, substeps) one advance(T) may take
  // per dt of T. Nothing else bounds the adaptive step's work: at its floor on a
  // stiff, light cloth one refresh interval can need millions of steps. When the
  // budget runs out, advance() stops early with a healthy state and says so
  // (Simulation::budget_exhausted()); a plain fixed step never reaches it.
  long step_budget = 10000;
  // Fixed steps only: a dt above step_cap() (the explicit stability bound times
  // `safety`) is taken as equal substeps under it instead of as one unstable
  // step. Off by default: a batch run asked for that step and gets it (a
  // divergence then says it was too large); the live simulation thread turns it
  // on, so a change made while the cloth moves cannot make it explode.
  bool substep_above_cap = false;
  // The projective integrator's local-global iterations per step: its accuracy
  // knob (more converge to the implicit Euler solution). Other integrators ignore it.
  int iterations = kDefaultProjectiveIterations;
  // The implicit_euler step's conjugate gradient stops at a residual of this
  // fraction of its right-hand side. A setting rather than a function of
  // `--accuracy`: that picks a measured (integrator, dt, iterations) row, and
  // the trade does not sweep this yet. Other integrators ignore it.
  double linear_tolerance = kDefaultLinearTolerance;
  // Threads that share each sweep of a step on a cloth of at least
  // kMinThreadedNodes nodes (step_threads.h). The results are bit-identical
  // to one thread's; only the wall time changes. 1: the calling thread alone.
  int threads = 1;
  // The spring layer's force neurons in double (the default) or float, where
  // a user asks for speed; docs/network.md, "Float springs", gives its
  // measured error. Explicit integrators only: the implicit ones linearise the
  // same springs in double, and learning differentiates the double step.
  SpringPrecision precision = SpringPrecision::float64;
  // Which code evaluates those force neurons (spring_kernel.h): automatic (the
  // AVX-512 kernel where the CPU has it), or one named, so that a test or a
  // benchmark runs the portable kernel on an AVX-512 machine too. Not a scene
  // field: a scene's results do not depend on it beyond the last bits.
  SpringKernel kernel = SpringKernel::automatic;
  // The springs' damping: in the force sum, as the paper has it (explicit), or
  // taken implicitly spring by spring after the velocity update (implicit,
  // spring_damping.h), which lifts the damping's bound on the step. The
  // network integrator only; docs/stability.md, "Damping taken implicitly".
  DampingMode damping = DampingMode::explicit_force;
  // Which bound caps the explicit steps (stability.h): the spectrum's, or
  // Gershgorin's discs (the bound before; a comparison, and what a ramp uses
  // while its weights move). docs/stability.md, "The spectral bound".
  StepBound step_bound = StepBound::spectral;
  // What preconditions the implicit_euler step's conjugate gradient. Not a
  // scene field, as `kernel`: a test or a benchmark compares them; the step
  // solves the same system to the same tolerance whichever it is.
  ImplicitPreconditioner implicit_preconditioner = ImplicitPreconditioner::automatic;
};

// The integrator these settings ask for, sized for `net` (make_integrator with
// every setting it takes, in one place).
inline std::unique_ptr<Integrator> make_integrator(const SolverSettings& s,
                                                   const ClothNetwork& net) {
  return make_integrator(s.integrator, net, s.adaptive_settings.min_step_fraction, s.iterations,
                         s.linear_tolerance, s.implicit_preconditioner,
                         s.damping == DampingMode::implicit_springwise);
}

// Why `precision` cannot go with `integrator`, or "" when it can. The implicit
// integrators' Newton and local-global solves pair the forces with a double
// linearisation of the same springs: float forces would only add noise to
// what they converge to, and they are not where those steps spend their time.
inline std::string precision_conflict(IntegratorKind integrator, SpringPrecision precision) {
  if (precision == SpringPrecision::float64) return "";
  if (integrator != IntegratorKind::implicit_euler && !iterates_per_step(integrator)) return "";
  return std::string(
             "\"float\" is for the explicit integrators (network, explicit_euler, "
             "verlet, rk4), not ") +
         to_string(integrator);
}

// Throws std::invalid_argument naming the first field out of its range
// ("solver.dt must be a finite number > 0, got -1"); the same limits as a scene file.
inline void validate(const SolverSettings& s) {
  auto fail = [](const std::string& field, const std::string& rule, double value) {
    std::ostringstream os;
    os << "solver." << field << " must be " << rule << ", got " << value;
    throw std::invalid_argument(os.str());
  };
  if (std::find(std::begin(kAllIntegrators), std::end(kAllIntegrators), s.integrator) ==
      std::end(kAllIntegrators))
    fail("integrator", "one of " + integrator_names(), static_cast<double>(s.integrator));
  // The one floor on every step a run is asked to take (a scene, --dt, a trade
  // row, the viewer): below it a run of seconds would take millions of steps.
  if (!limits::kTimeStep.contains(s.dt))
    fail("dt", "in [1e-06, 1e+09] s (" + std::string(limits::kTimeStep.meaning) + ")", s.dt);
  const AdaptiveSettings& a = s.adaptive_settings;
  if (!(a.safety > 0 && a.safety <= 1)) fail("safety", "in (0, 1]", a.safety);
  if (!limits::kGrowthTolerance.contains(a.growth_tolerance))
    fail("growth_tolerance", "in [0, 1000]", a.growth_tolerance);
  if (!limits::kStepFraction.contains(a.min_step_fraction))
    fail("min_step_fraction", "in [1e-06, 1]", a.min_step_fraction);
  const DivergenceSettings& d = s.divergence;
  if (!limits::kCheckInterval.contains(d.check_interval))
    fail("check_interval", "in [1, 1000000]", d.check_interval);
  if (!(d.runaway_factor >= 1)) fail("runaway_factor", ">= 1", d.runaway_factor);
  if (d.runaway_checks < 1) fail("runaway_checks", ">= 1", d.runaway_checks);
  if (!(d.hard_factor >= d.runaway_factor)) fail("hard_factor", ">= runaway_factor", d.hard_factor);
  if (s.step_budget < 1) fail("step_budget", ">= 1", static_cast<double>(s.step_budget));
  // Their iterations are tuned to one step (projective's factor, both
  // Chebyshev rates); the adaptive rule would ask for new ones at every trial
  // (docs/network.md, "Large steps").
  if (iterates_per_step(s.integrator) && s.adaptive)
    fail("adaptive",
         std::string("false for the ") + to_string(s.integrator) +
             " integrator, which takes fixed steps",
         1);
  if (!limits::kIterations.contains(s.iterations))
    fail("iterations", "in [1, 1000]", static_cast<double>(s.iterations));
  if (!limits::kLinearTolerance.contains(s.linear_tolerance))
    fail("linear_tolerance", "in [1e-14, 0.01]", s.linear_tolerance);
  if (s.precision != SpringPrecision::float64 && s.precision != SpringPrecision::float32)
    fail("precision", std::string("one of ") + kPrecisionNames, static_cast<double>(s.precision));
  const std::string conflict = precision_conflict(s.integrator, s.precision);
  if (!conflict.empty()) throw std::invalid_argument("solver.precision " + conflict);
  if (s.kernel != SpringKernel::automatic && s.kernel != SpringKernel::portable &&
      s.kernel != SpringKernel::avx512)
    fail("kernel", std::string("one of ") + kKernelNames, static_cast<double>(s.kernel));
  const std::string missing = kernel_unavailable(s.kernel);
  if (!missing.empty()) throw std::invalid_argument("solver.kernel avx512: " + missing);
  if (s.damping != DampingMode::explicit_force && s.damping != DampingMode::implicit_springwise)
    fail("damping", std::string("one of ") + kDampingNames, static_cast<double>(s.damping));
  if (s.damping == DampingMode::implicit_springwise && s.integrator != IntegratorKind::network)
    throw std::invalid_argument(
        std::string("solver.damping \"implicit\" is for the network integrator, not ") +
        to_string(s.integrator));
  if (s.implicit_preconditioner != ImplicitPreconditioner::automatic &&
      s.implicit_preconditioner != ImplicitPreconditioner::laplacian &&
      s.implicit_preconditioner != ImplicitPreconditioner::multigrid &&
      s.implicit_preconditioner != ImplicitPreconditioner::jacobi)
    fail("implicit_preconditioner", std::string("one of ") + kImplicitPreconditionerNames,
         static_cast<double>(s.implicit_preconditioner));
  if (s.threads < 1 || s.threads > kMaxStepThreads)
    fail("threads", "in [1, " + std::to_string(kMaxStepThreads) + "]",
         static_cast<double>(s.threads));
}

}  // namespace neurocloth
