// The driver around the integrators: the paper's adaptive rule (Table 1) with
// rollback, divergence detection that keeps the last good state, determinism.
#include "core/simulation/simulation.h"

#include <gtest/gtest.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <cmath>

#include "support/test_support.h"

namespace neurocloth {
namespace {

Scene adaptive_hanging(IntegratorKind kind) {
  Scene scene = test::asset_scene("hanging");
  scene.solver.integrator = kind;
  scene.solver.adaptive = true;
  scene.solver.dt = 0.04;  // the paper's refresh interval t_delta
  return scene;
}

// Replays Table 1 from the recorded trials: every rejection halves t_c and
// leaves t where it was; every acceptance advances t by the step and doubles
// t_c (up to the cap); a trial is rejected exactly when its max force grew
// beyond the tolerance and t_c was above its floor.
TEST(Simulation, AdaptiveRuleHalvesAndDoublesAsTable1) {
  const Scene scene = adaptive_hanging(IntegratorKind::network);
  Simulation sim = scene.make_simulation();
  std::vector<StepEvent> frame;
  sim.set_observer([&](const StepEvent& e) { frame.push_back(e); });
  const double cap = sim.step_cap();
  const AdaptiveSettings& A = scene.solver.adaptive_settings;
  const double floor = cap * A.min_step_fraction;
  double weight = 0;
  for (std::size_t i = 0; i < sim.network().node_count(); ++i)
    if (sim.network().masses.free[i] != 0) weight = std::max(weight, sim.network().mass(i) * 9.81);
  ASSERT_LT(cap, scene.solver.dt);  // the stability bound, not t_delta, limits t_c here

  long rejected = 0, accepted = 0;
  for (int f = 0; f < 25; ++f) {  // one second, frame by frame
    frame.clear();
    const double t0 = sim.time();
    sim.advance(scene.solver.dt);
    ASSERT_FALSE(frame.empty());
    EXPECT_EQ(frame.front().tc, cap);  // Table 1: t_c := t_delta (capped)
    EXPECT_EQ(frame.front().time, t0);
    for (std::size_t i = 0; i < frame.size(); ++i) {
      const StepEvent& e = frame[i];
      const bool grew = e.max_force > e.former_max_force +
                                          A.growth_tolerance * std::max(e.former_max_force, weight);
      EXPECT_EQ(e.accepted, !grew || e.tc <= floor) << "frame " << f << " trial " << i;
      (e.accepted ? accepted : rejected) += 1;
      if (i + 1 == frame.size()) break;
      const StepEvent& next = frame[i + 1];
      if (e.accepted) {
        EXPECT_DOUBLE_EQ(next.time, e.time + e.step);
        EXPECT_EQ(next.tc, std::min(2 * e.tc, cap));
        EXPECT_EQ(next.former_max_force, e.max_force);
      } else {
        EXPECT_EQ(next.time, e.time);  // rolled back: t unchanged
        EXPECT_EQ(next.tc, std::max(0.5 * e.tc, floor));
        EXPECT_EQ(next.former_max_force, e.former_max_force);
      }
    }
    EXPECT_NEAR(sim.time(), t0 + scene.solver.dt, 1e-12);
  }
  EXPECT_GT(rejected, 10);  // the rule was really exercised
  EXPECT_GT(accepted, 100);
  EXPECT_EQ(sim.rejected_steps(), rejected);
  EXPECT_EQ(sim.steps(), accepted);
}

// Rollback: the adaptive run's state equals, bit for bit, a plain replay of only
// its accepted steps — rejected trials left no trace.
TEST(Simulation, RejectedTrialsLeaveNoTrace) {
  for (IntegratorKind kind : {IntegratorKind::network, IntegratorKind::rk4}) {
    const Scene scene = adaptive_hanging(kind);
    Simulation sim = scene.make_simulation();
    std::vector<double> steps;
    long rejected = 0;
    sim.set_observer([&](const StepEvent& e) {
      if (e.accepted)
        steps.push_back(e.step);
      else
        ++rejected;
    });
    sim.advance(0.4);
    ASSERT_GT(rejected, 0) << to_string(kind);

    const ClothNetwork net = scene.build_network();
    auto integrator = make_integrator(kind, net);
    ClothState a = scene.initial_state(), b = a;
    NodeVectors F(a.size());
    for (double h : steps) {
      net.net_forces(a, F);
      integrator->step(net, ForceInputs{}, ForceContext{}, a, F, h, b);
      std::swap(a, b);
    }
    EXPECT_EQ(test::state_hash(a), test::state_hash(sim.state())) << to_string(kind);
  }
}

TEST(Simulation, AdaptiveStepNeverExceedsTheStabilityCap) {
  Simulation sim = adaptive_hanging(IntegratorKind::verlet).make_simulation();
  const double cap = sim.step_cap();
  double largest = 0;
  sim.set_observer([&](const StepEvent& e) { largest = std::max(largest, e.step); });
  sim.advance(1.0);
  EXPECT_EQ(sim.status(), RunStatus::ok);
  EXPECT_LE(largest, cap);
  EXPECT_GT(largest, 0.49 * cap);
}

// Far beyond the stability limit the run must stop as diverged, keep a finite
// state, and that state must be exactly the one the same run reaches at the
// reported time: the last accepted (checked) step.
TEST(Simulation, DivergenceKeepsTheLastGoodState) {
  for (IntegratorKind kind : {IntegratorKind::explicit_euler, IntegratorKind::network}) {
    Scene scene = test::asset_scene("hanging");
    scene.solver.integrator = kind;
    scene.solver.dt = 0.01;  // several times the explicit limit for this cloth
    scene.solver.divergence.check_interval = 8;
    Simulation sim = scene.make_simulation();
    EXPECT_EQ(sim.advance(5.0), RunStatus::diverged) << to_string(kind);
    EXPECT_FALSE(sim.divergence_reason().empty());
    EXPECT_TRUE(sim.state().all_finite());
    EXPECT_TRUE(std::isfinite(sim.energy().total()));
    EXPECT_LT(sim.time(), 5.0);
    EXPECT_EQ(sim.steps() % 8, 0);
    // Further advancing does nothing.
    const auto hash = test::state_hash(sim.state());
    sim.advance(1.0);
    EXPECT_EQ(test::state_hash(sim.state()), hash);

    Simulation replay = scene.make_simulation();
    replay.advance(sim.steps() * scene.solver.dt);
    EXPECT_EQ(replay.steps(), sim.steps());
    EXPECT_EQ(test::state_hash(replay.state()), hash) << to_string(kind);
  }
}

// An implicit step on a very stiff cloth can lift the energy for a step or two;
// that transient must not be called a divergence.
TEST(Simulation, ImplicitTransientOnAStiffClothIsNotRunaway) {
  Scene scene = test::asset_scene("hanging");
  scene.material.spring_constant = 1e7;
  scene.solver.integrator = IntegratorKind::implicit_euler;
  scene.solver.dt = 0.02;
  Simulation sim = scene.make_simulation();
  EXPECT_EQ(sim.advance(1.0), RunStatus::ok) << sim.divergence_reason();
  EXPECT_TRUE(sim.state().all_finite());
}

TEST(Simulation, ZeroSecondsIsTheInitialState) {
  const Scene scene = test::asset_scene("hanging");
  Simulation sim = scene.make_simulation();
  sim.advance(0.0);
  EXPECT_EQ(sim.steps(), 0);
  EXPECT_EQ(sim.time(), 0.0);
  EXPECT_EQ(test::state_hash(sim.state()), test::state_hash(scene.initial_state()));
}

TEST(Simulation, PinnedNodesDoNotMoveAndTimeLandsExactly) {
  const Scene scene = test::asset_scene("hanging");
  for (IntegratorKind kind : kAllIntegrators) {
    Scene s = scene;
    s.solver.integrator = kind;
    Simulation sim = s.make_simulation();
    sim.advance(0.2555);  // not a multiple of dt: the last step is shortened
    EXPECT_EQ(sim.time(), 0.2555);
    for (int pin : scene.pins)
      EXPECT_EQ(sim.state().position(pin), scene.topology.rest_positions[pin]);
    EXPECT_LT(sim.state().y[210], scene.topology.rest_positions[210].y() - 0.01);  // the rest fell
  }
}

TEST(Simulation, ExternalForceCanBeSetOnAnyNodeAtAnyTime) {
  const Scene scene = test::asset_scene("hanging");
  Simulation pushed = scene.make_simulation(), free = scene.make_simulation();
  pushed.advance(0.1);
  free.advance(0.1);
  pushed.set_external_force(399, Vec3(2.0, 0, 0));  // the far corner, sideways
  pushed.advance(0.2);
  free.advance(0.2);
  EXPECT_GT(pushed.state().x[399] - free.state().x[399], 0.01);
  pushed.set_external_force(399, Vec3::Zero());
  EXPECT_EQ(pushed.force_inputs().external_force.at(399), Vec3::Zero());
}

// An interrupt asked between frames stops advance() there, and what was run
// is exactly an uninterrupted run of that many frames: fixed and adaptive,
// with modules whose forces depend on time (the flag's gusts, the curtain's
// moving rail).
TEST(Simulation, AnInterruptStopsBetweenFramesOnTheUninterruptedPath) {
  for (const char* name : {"hanging", "table_drape", "flag", "curtain"}) {
    SCOPED_TRACE(name);
    const Scene scene = test::asset_scene(name);
    Simulation cut = scene.make_simulation();
    int frames = 0;
    cut.set_interrupt([&](const Simulation&) { return ++frames == 7; });
    EXPECT_EQ(cut.advance(1e300), RunStatus::ok);
    EXPECT_TRUE(cut.interrupted());
    EXPECT_EQ(frames, 7);
    // advance(k dt) and k calls of advance(dt) take the same steps, bit for bit.
    Simulation whole = scene.make_simulation();
    for (int i = 0; i < 7; ++i)
      whole.advance(scene.solver.dt);
    EXPECT_EQ(cut.time(), whole.time());
    EXPECT_EQ(cut.steps(), whole.steps());
    EXPECT_EQ(test::state_hash(cut.state()), test::state_hash(whole.state()));
    // The flag clears with the next call, which runs on.
    cut.set_interrupt({});
    cut.advance(scene.solver.dt);
    EXPECT_FALSE(cut.interrupted());
    EXPECT_GT(cut.steps(), whole.steps());
  }
}

}  // namespace
}  // namespace neurocloth

namespace neurocloth {
namespace {

// A moved simulation keeps stepping its own buffers (not the moved-from
// object's): the same bits as one that never moved, mid-run and with modules.
// The shipped hanging cloth 0.5 s (500 steps, from rest through its first
// swing) under `precision`; its positions.
std::vector<Vec3> hanging_after(SpringPrecision precision) {
  Scene scene = test::asset_scene("hanging");
  scene.solver.precision = precision;
  Simulation sim = scene.make_simulation();
  EXPECT_EQ(sim.advance(0.5), RunStatus::ok);
  std::vector<Vec3> p;
  for (std::size_t i = 0; i < sim.state().size(); ++i)
    p.push_back(sim.state().position(i));
  return p;
}

// Float springs (SolverSettings::precision) keep the double run's motion. Each
// float force is its double value to a few float ulp (8 epsilon of the
// spring's scale, cloth_network_test.cpp), i.e. the force of a rest length
// off by 8 epsilon. A stable cloth settles where such perturbed springs put
// it: along a chain of springs the offsets add up to at most 8 epsilon of the
// chain's length, below the cloth's size. A further factor 8 allows for the
// swing's phase; a float path that dropped its Newton step (6e-5 per force)
// lands further off.
TEST(Simulation, FloatSpringsStayWithinFloatRoundOffOfDouble) {
  const std::vector<Vec3> in_double = hanging_after(SpringPrecision::float64);
  const std::vector<Vec3> in_float = hanging_after(SpringPrecision::float32);
  Vec3 lo = in_double[0], hi = in_double[0];
  for (const Vec3& p : in_double) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double size = (hi - lo).norm();
  const double epsilon = 1.1920928955078125e-7;  // float's, 2^-23
  double worst = 0;
  for (std::size_t i = 0; i < in_double.size(); ++i)
    worst = std::max(worst, (in_float[i] - in_double[i]).norm());
  EXPECT_LT(worst, 64 * epsilon * size);
  EXPECT_GT(worst, 0.0) << "the float path computed in double";
}

// Determinism per build holds for the float path too: the same run twice, the same bits.
TEST(Simulation, FloatSpringsAreDeterministic) {
  EXPECT_EQ(hanging_after(SpringPrecision::float32), hanging_after(SpringPrecision::float32));
}

// Float is refused by name where it has no meaning: the implicit integrators.
TEST(Simulation, FloatPrecisionIsRefusedForTheImplicitIntegratorsByName) {
  for (const IntegratorKind kind :
       {IntegratorKind::implicit_euler, IntegratorKind::projective, IntegratorKind::vbd}) {
    SolverSettings settings;
    settings.integrator = kind;
    settings.precision = SpringPrecision::float32;
    try {
      validate(settings);
      ADD_FAILURE() << to_string(kind) << " accepted float";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("solver.precision"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(to_string(kind)), std::string::npos) << e.what();
    }
  }
  SolverSettings explicit_float;
  explicit_float.precision = SpringPrecision::float32;
  for (const IntegratorKind kind : {IntegratorKind::network, IntegratorKind::explicit_euler,
                                    IntegratorKind::verlet, IntegratorKind::rk4}) {
    explicit_float.integrator = kind;
    EXPECT_NO_THROW(validate(explicit_float)) << to_string(kind);
  }
}

TEST(SimulationMove, AMovedSimulationStepsItsOwnBuffers) {
  const Scene scene = test::asset_scene("curtain");
  Simulation stay = scene.make_simulation();
  auto first = std::make_unique<Simulation>(scene.make_simulation());
  stay.advance(0.05);
  first->advance(0.05);
  Simulation moved(std::move(*first));
  first.reset();  // nothing of the moved-from object may still be in use
  stay.advance(0.05);
  moved.advance(0.05);
  EXPECT_EQ(test::state_hash(moved.state()), test::state_hash(stay.state()));
  EXPECT_EQ(moved.steps(), stay.steps());
}

}  // namespace
}  // namespace neurocloth
