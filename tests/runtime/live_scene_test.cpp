// Commands applied to a running scene, on one thread: each reaches the network
// (or is refused with a message naming the parameter and its range), and a
// refused command changes nothing.
#include "runtime/live_scene.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "support/scratch_dir.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

using test::contains;

bool all_equal(const std::vector<double>& v, double x) {
  return std::all_of(v.begin(), v.end(), [x](double e) { return e == x; });
}

std::vector<std::string> names(const std::vector<ParameterRange>& ranges) {
  std::vector<std::string> n;
  for (const ParameterRange& r : ranges)
    n.push_back(r.name);
  return n;
}

TEST(LiveScene, RangesDependOnTheScene) {
  using V = std::vector<std::string>;
  const V base = {"viscosity", "friction", "dt", "gravity.x", "gravity.y", "gravity.z"};
  EXPECT_EQ(names(parameter_ranges(test::asset_scene("hanging"))), base);
  V wind = base;
  wind.insert(wind.end(), {"wind.velocity.x", "wind.velocity.y", "wind.velocity.z"});
  EXPECT_EQ(names(parameter_ranges(test::asset_scene("flag"))), wind);

  // A fuzzy material adds its rule base's inputs, with the rule base's ranges.
  const Scene fuzzy = test::asset_scene("hanging_fuzzy");
  const auto ranges = parameter_ranges(fuzzy);
  const FuzzyMaterial& rules = *fuzzy.fuzzy_material->rules;
  ASSERT_EQ(ranges.size(), base.size() + rules.system().inputs.size());
  for (const auto& v : rules.system().inputs) {
    const ParameterRange* r = find_range(ranges, test::parameter(fuzzy, "input." + v.name));
    ASSERT_NE(r, nullptr) << v.name;
    EXPECT_EQ(r->min, v.min);
    EXPECT_EQ(r->max, v.max);
  }
  const ParameterRange* visc = find_range(ranges, test::parameter("viscosity"));
  ASSERT_NE(visc, nullptr);
  EXPECT_EQ(describe_range(*visc), "[0, 100] N s/m");
  const ParameterId wind_x = ParameterId::module(0, ModuleParameter::velocity, 0);
  EXPECT_EQ(find_range(ranges, wind_x), nullptr);
}

TEST(LiveScene, ViscosityAndFrictionReachEverySpringAndNode) {
  LiveScene live(test::asset_scene("hanging"));
  EXPECT_EQ(live.apply(SetParameter{test::parameter("viscosity"), 2.5}), "");
  EXPECT_EQ(live.apply(SetParameter{test::parameter("friction"), 0.7}), "");
  EXPECT_TRUE(all_equal(live.simulation().network().springs.damping, 2.5));
  EXPECT_TRUE(all_equal(live.simulation().network().masses.friction, 0.7));
  SimulationStatus s;
  live.describe(s);
  EXPECT_EQ(s.viscosity, 2.5);
  EXPECT_EQ(s.friction, 0.7);
}

TEST(LiveScene, SolverParametersReachTheSimulation) {
  LiveScene live(test::asset_scene("hanging"));
  EXPECT_EQ(live.apply(SetParameter{test::parameter("dt"), 2e-4}), "");
  EXPECT_EQ(live.apply(SetIntegrator{IntegratorKind::rk4}), "");
  EXPECT_EQ(live.apply(SetAdaptive{true}), "");
  const SolverSettings& s = live.simulation().settings();
  EXPECT_EQ(s.dt, 2e-4);
  EXPECT_EQ(s.integrator, IntegratorKind::rk4);
  EXPECT_TRUE(s.adaptive);
  EXPECT_EQ(live.apply(SetParameter{test::parameter("gravity.x"), 3}), "");
  EXPECT_EQ(live.simulation().network().gravity, Vec3(3, -9.81, 0));
}

// The accuracy slider's command: every solver field at once, the live run's
// guards kept; a bad one changes nothing.
TEST(LiveScene, ASolverSetAsAWholeReachesTheSimulationOrIsRefused) {
  LiveScene live(test::asset_scene("hanging"));
  const SolverSettings before = live.simulation().settings();
  EXPECT_EQ(live.apply(SetSolver{IntegratorKind::rk4, 5e-4, false, 0.5, 10, 1e-10}), "");
  const SolverSettings& s = live.simulation().settings();
  EXPECT_EQ(s.integrator, IntegratorKind::rk4);
  EXPECT_EQ(s.dt, 5e-4);
  EXPECT_FALSE(s.adaptive);
  EXPECT_EQ(s.adaptive_settings.safety, 0.5);
  EXPECT_EQ(s.substep_above_cap, before.substep_above_cap);
  EXPECT_EQ(s.step_budget, before.step_budget);
  EXPECT_EQ(live.apply(SetSolver{IntegratorKind::projective, 0.01, false, 0.5, 4, 1e-10}), "");
  EXPECT_EQ(live.simulation().settings().integrator, IntegratorKind::projective);
  EXPECT_EQ(live.simulation().settings().iterations, 4);
  EXPECT_EQ(live.apply(SetSolver{IntegratorKind::network, 0.01, true, 0.25, 10, 1e-10}), "");
  EXPECT_TRUE(live.simulation().settings().adaptive);
  EXPECT_EQ(live.simulation().settings().adaptive_settings.safety, 0.25);
  EXPECT_EQ(live.apply(SetSolver{IntegratorKind::implicit_euler, 0.01, false, 0.5, 10, 1e-4}), "");
  EXPECT_EQ(live.simulation().settings().linear_tolerance, 1e-4);
  EXPECT_EQ(live.apply(SetSolver{IntegratorKind::network, 0.01, true, 0.25, 10, 1e-10}), "");

  EXPECT_TRUE(
      contains(live.apply(SetSolver{IntegratorKind::rk4, 0.5, false, 0.5, 10, 1e-10}), "dt"));
  EXPECT_TRUE(
      contains(live.apply(SetSolver{IntegratorKind::rk4, 1e-3, true, 0, 10, 1e-10}), "safety"));
  EXPECT_TRUE(contains(
      live.apply(SetSolver{IntegratorKind::projective, 1e-3, false, 0.5, 0, 1e-10}), "iterations"));
  EXPECT_TRUE(
      contains(live.apply(SetSolver{IntegratorKind::implicit_euler, 1e-3, false, 0.5, 10, 0.5}),
               "linear_tolerance"));
  EXPECT_FALSE(
      live.apply(SetSolver{static_cast<IntegratorKind>(42), 1e-3, false, 0.5, 10, 1e-10}).empty());
  EXPECT_EQ(live.simulation().settings().integrator, IntegratorKind::network) << "unchanged";
  EXPECT_EQ(live.simulation().settings().dt, 0.01);
}

// solver_command: settings sent as one command arrive whole (the accuracy
// slider's pick and the scene's own solver back both go this way).
TEST(LiveScene, SolverSettingsSentAsOneCommandArriveWhole) {
  LiveScene live(test::asset_scene("hanging"));
  SolverSettings s = live.simulation().settings();
  s.integrator = IntegratorKind::projective;
  s.dt = 1.0 / 64;
  s.adaptive = false;
  s.adaptive_settings.safety = 0.3;
  s.iterations = 3;
  EXPECT_EQ(live.apply(solver_command(s)), "");
  const SolverSettings& got = live.simulation().settings();
  EXPECT_EQ(got.integrator, IntegratorKind::projective);
  EXPECT_EQ(got.dt, 1.0 / 64);
  EXPECT_FALSE(got.adaptive);
  EXPECT_EQ(got.adaptive_settings.safety, 0.3);
  EXPECT_EQ(got.iterations, 3);
}

TEST(LiveScene, OutOfRangeAndUnknownParametersAreRefusedAndChangeNothing) {
  LiveScene live(test::asset_scene("hanging"));
  const std::string high = live.apply(SetParameter{test::parameter("viscosity"), 500});
  EXPECT_TRUE(contains(high, "viscosity")) << high;
  EXPECT_TRUE(contains(high, "[0, 100] N s/m")) << high;
  EXPECT_TRUE(contains(live.apply(SetParameter{test::parameter("dt"), 0.5}), "[1e-05, 0.1] s"));
  EXPECT_TRUE(
      contains(live.apply(SetParameter{test::parameter("friction"), std::nan("")}), "friction"));
  // Ids parsed against another scene: a module or an input this one lacks.
  const std::string unknown =
      live.apply(SetParameter{ParameterId::module(0, ModuleParameter::velocity, 0), 1});
  EXPECT_TRUE(contains(unknown, "unknown parameter 'module#0'")) << unknown;
  EXPECT_TRUE(contains(unknown, "viscosity")) << unknown;  // lists what there is
  EXPECT_TRUE(contains(live.apply(SetParameter{ParameterId::input(0), 0.5}), "unknown parameter"));
  EXPECT_FALSE(live.apply(SetIntegrator{static_cast<IntegratorKind>(42)}).empty());
  EXPECT_TRUE(all_equal(live.simulation().network().springs.damping, 0.05));
  EXPECT_EQ(live.simulation().settings().dt, 1e-3);
  EXPECT_EQ(live.simulation().settings().integrator, IntegratorKind::network);
}

TEST(LiveScene, NodeIndicesAreChecked) {
  LiveScene live(test::asset_scene("hanging"));
  const int n = static_cast<int>(live.simulation().network().node_count());
  for (int bad : {-1, n}) {
    const std::string why = live.apply(ApplyForce{bad, Vec3(1, 0, 0), Vec3::Zero()});
    EXPECT_TRUE(contains(why, "node " + std::to_string(bad))) << why;
    EXPECT_TRUE(contains(why, "0.." + std::to_string(n - 1))) << why;
    EXPECT_FALSE(live.apply(ReleaseForce{bad}).empty());
    EXPECT_FALSE(live.apply(SetPinned{bad, true}).empty());
  }
  EXPECT_FALSE(live.apply(ApplyForce{3, Vec3(std::nan(""), 0, 0), Vec3::Zero()}).empty());
  EXPECT_TRUE(live.forces().empty());
}

TEST(LiveScene, ForcesAreRememberedUntilReleased) {
  LiveScene live(test::asset_scene("hanging"));
  EXPECT_EQ(live.apply(ApplyForce{399, Vec3(0, 0, 0.5), Vec3(0, 0, 2)}), "");
  EXPECT_EQ(live.apply(ApplyForce{399, Vec3(0, 0, 0.7), Vec3(0, 0, 3)}), "");  // a drag moves on
  ASSERT_EQ(live.forces().size(), 1u);
  EXPECT_EQ(live.forces()[0].force, Vec3(0, 0, 0.7));
  EXPECT_EQ(live.forces()[0].anchor, Vec3(0, 0, 3));
  EXPECT_EQ(live.simulation().force_inputs().external_force.at(399), Vec3(0, 0, 0.7));
  EXPECT_EQ(live.apply(ReleaseForce{399}), "");
  EXPECT_EQ(live.apply(ReleaseForce{398}), "");  // not pulled: nothing to do, not an error
  EXPECT_TRUE(live.forces().empty());
  EXPECT_EQ(live.simulation().force_inputs().external_force.at(399), Vec3::Zero());
}

// A linguistic input ramps the weights to the rule base's material for the new
// inputs; the user's viscosity survives it.
TEST(LiveScene, InputChangeRampsToTheDerivedMaterialKeepingTheUsersViscosity) {
  const Scene scene = test::asset_scene("hanging_fuzzy");
  LiveScene live(scene);
  EXPECT_EQ(live.apply(SetParameter{test::parameter("viscosity"), 0.3}), "");
  EXPECT_EQ(live.apply(SetParameter{test::parameter(scene, "input.mass"), 0.9}), "");
  EXPECT_TRUE(live.simulation().ramping());
  for (int frame = 0; frame < 100 && live.simulation().ramping(); ++frame)
    live.simulation().advance(0.01);  // the ramp takes 64 accepted steps
  ASSERT_FALSE(live.simulation().ramping());

  std::map<std::string, double> inputs = scene.fuzzy_material->inputs;
  inputs["mass"] = 0.9;
  Material expected = scene.fuzzy_material->rules->derive(inputs).material;
  expected.viscosity = 0.3;
  Scene target_scene = scene;
  target_scene.material = expected;
  const ClothNetwork target = target_scene.build_network();
  const ClothNetwork& net = live.simulation().network();
  EXPECT_EQ(net.springs.stiffness, target.springs.stiffness);
  EXPECT_EQ(net.masses.inverse_mass, target.masses.inverse_mass);
  EXPECT_TRUE(all_equal(net.springs.damping, 0.3));

  SimulationStatus s;
  live.describe(s);
  const auto mass = std::find_if(s.material_inputs.begin(), s.material_inputs.end(),
                                 [](const auto& p) { return p.first == "mass"; });
  ASSERT_NE(mass, s.material_inputs.end());
  EXPECT_EQ(mass->second, 0.9);
  EXPECT_TRUE(
      contains(live.apply(SetParameter{test::parameter(scene, "input.mass"), 7}), "input.mass"));
}

TEST(LiveScene, WindChangesOnlyInWindScenes) {
  LiveScene live(test::asset_scene("flag"));
  SimulationStatus before;
  live.describe(before);
  ASSERT_TRUE(before.wind.has_value());
  EXPECT_EQ(*before.wind, Vec3(6, 0, 0.8));
  NodeVectors f0(live.simulation().network().node_count());
  live.simulation().network().net_forces(live.simulation().state(), f0);

  EXPECT_EQ(live.apply(SetParameter{test::parameter(live.scene(), "wind.velocity.x"), -20}), "");
  EXPECT_TRUE(
      contains(live.apply(SetParameter{test::parameter(live.scene(), "wind.velocity.z"), 80}),
               "[-50, 50] m/s"));
  SimulationStatus after;
  live.describe(after);
  EXPECT_EQ(*after.wind, Vec3(-20, 0, 0.8));
  NodeVectors f1(f0.size());
  live.simulation().network().net_forces(live.simulation().state(), f1);
  double sum0 = 0, sum1 = 0;
  for (std::size_t i = 0; i < f0.size(); ++i) {
    sum0 += f0.x[i];
    sum1 += f1.x[i];
  }
  EXPECT_GT(sum0, 0);  // downwind along +x before, along -x after
  EXPECT_LT(sum1, 0);
}

TEST(LiveScene, ResetRestoresTheScenesStateAndParameters) {
  const Scene scene = test::asset_scene("hanging");
  LiveScene live(scene, true);
  const long generation = live.generation();
  live.apply(SetParameter{test::parameter("viscosity"), 4});
  live.apply(SetParameter{test::parameter("dt"), 5e-4});
  live.apply(SetPinned{0, false});
  live.apply(ApplyForce{10, Vec3(1, 0, 0), Vec3::Zero()});
  live.simulation().advance(0.05);
  EXPECT_EQ(live.apply(Reset{}), "");
  EXPECT_GT(live.generation(), generation);
  EXPECT_TRUE(live.paused());  // pausing is the user's, not the scene's
  const Simulation fresh = scene.make_simulation();
  EXPECT_EQ(test::state_hash(live.simulation().state()), test::state_hash(fresh.state()));
  EXPECT_EQ(live.simulation().time(), 0);
  EXPECT_EQ(live.simulation().settings().dt, 1e-3);
  EXPECT_TRUE(all_equal(live.simulation().network().springs.damping, 0.05));
  EXPECT_TRUE(live.simulation().network().masses.pinned(0));
  EXPECT_TRUE(live.forces().empty());
}

TEST(LiveScene, PauseAndSingleStep) {
  LiveScene live(test::asset_scene("hanging"));
  EXPECT_TRUE(contains(live.apply(SingleStep{}), "only while paused"));
  EXPECT_EQ(live.simulation().time(), 0);
  EXPECT_EQ(live.apply(SetPaused{true}), "");
  EXPECT_EQ(live.apply(SingleStep{}), "");
  EXPECT_EQ(live.simulation().time(), 1e-3);
  EXPECT_EQ(live.simulation().steps(), 1);
}

// The thread's stop cuts a long Advance short between frames; nothing is owed
// after it, and the next Advance runs whole.
TEST(LiveScene, TheStopCheckCutsAnAdvanceShort) {
  LiveScene live(test::asset_scene("hanging"));  // dt 1e-3 s
  int asks = 0;
  live.set_stop_check([&] { return ++asks == 5; });
  EXPECT_TRUE(contains(live.apply(Advance{0.5}), "cut short at t = 0.005 s"));
  EXPECT_EQ(live.simulation().steps(), 5);
  live.set_stop_check({});
  EXPECT_EQ(live.apply(Advance{0.1}), "");
  EXPECT_EQ(live.simulation().steps(), 105);
}

TEST(LiveScene, ABrokenSceneOrRuleBaseLeavesTheRunAsItWas) {
  const std::string dir = test::scratch_dir().string();
  const std::string broken = dir + "/broken.json";
  std::ofstream(broken) << "{ \"name\": \"broken\", \"cloth\": { \"grid\": 3 } }";

  LiveScene live(test::asset_scene("hanging_fuzzy"));
  live.apply(SetParameter{test::parameter("viscosity"), 0.2});
  live.simulation().advance(0.02);
  const std::uint64_t before = test::state_hash(live.simulation().state());
  const long generation = live.generation();

  const std::string missing = live.apply(LoadScene{dir + "/missing.json"});
  EXPECT_TRUE(contains(missing, "missing.json")) << missing;
  const std::string bad = live.apply(LoadScene{broken});
  EXPECT_TRUE(contains(bad, "broken.json")) << bad;
  const std::string rules = live.apply(LoadRules{dir + "/missing.fcl"});
  EXPECT_TRUE(contains(rules, "missing.fcl")) << rules;

  EXPECT_EQ(live.generation(), generation);
  EXPECT_EQ(live.scene().name, "hanging_fuzzy");
  EXPECT_EQ(test::state_hash(live.simulation().state()), before);
  EXPECT_TRUE(all_equal(live.simulation().network().springs.damping, 0.2));

  EXPECT_EQ(live.apply(LoadScene{assets_directory() + "/scenes/flag.json"}), "");
  EXPECT_EQ(live.scene().name, "flag");
  EXPECT_GT(live.generation(), generation);
  EXPECT_TRUE(contains(live.apply(LoadRules{assets_directory() + "/materials/cloth.fcl"}),
                       "only a scene whose material is a rule base"));
}

// A scene the sender read is taken as it is (the path is not read again), and
// the status shares it with the UI.
TEST(LiveScene, ASceneSentAlongIsNotReadAgain) {
  LiveScene live(test::asset_scene("hanging"));
  auto flag = std::make_shared<const Scene>(test::asset_scene("flag"));
  EXPECT_EQ(live.apply(LoadScene{"/nonexistent/flag.json", flag}), "");
  EXPECT_EQ(live.scene().name, "flag");
  SimulationStatus status;
  live.describe(status);
  EXPECT_EQ(status.scene, flag);
}

TEST(LiveScene, NewRulesReplaceTheRuleBase) {
  LiveScene live(test::asset_scene("hanging_fuzzy"));
  const std::string path = assets_directory() + "/materials/cloth.fcl";
  EXPECT_EQ(live.apply(LoadRules{path}), "");
  EXPECT_EQ(live.scene().fuzzy_material->rules_path, path);
  EXPECT_NE(find_range(live.ranges(), test::parameter(live.scene(), "input.elasticity")), nullptr);
}

TEST(LiveScene, TheRuleBaseIsReadOnceWithTheScene) {
  const Scene scene = test::fuzzy_scene_without_its_rules(test::scratch_dir().string());
  ASSERT_TRUE(scene.fuzzy_material && scene.fuzzy_material->rules);
  EXPECT_EQ(parameter_ranges(scene).size(),
            all_parameters(ParameterNames{}).size() + scene.fuzzy_material->inputs.size());

  LiveScene live(scene);  // would throw if it read the rule base again
  const ParameterId mass = test::parameter(scene, "input.mass");
  EXPECT_NE(find_range(live.ranges(), mass), nullptr);
  EXPECT_EQ(live.apply(SetParameter{mass, 0.9}), "");
  EXPECT_TRUE(live.simulation().ramping());
  EXPECT_EQ(live.apply(Reset{}), "");
  EXPECT_EQ(live.apply(SetParameter{mass, 0.1}), "");
  EXPECT_EQ(live.scene().fuzzy_material->rules, scene.fuzzy_material->rules)
      << "shared, not copied";
}

// A rule base the sender has read already is taken as it is, not read again.
TEST(LiveScene, NewRulesReadByTheSenderAreNotReadAgain) {
  LiveScene live(test::asset_scene("hanging_fuzzy"));
  const auto rules = std::make_shared<const FuzzyMaterial>(
      FuzzyMaterial::load(assets_directory() + "/materials/cloth.fcl"));
  const std::string gone = std::string(NEUROCLOTH_TEST_TMP) + "/no_such_dir/cloth.fcl";
  EXPECT_EQ(live.apply(LoadRules{gone, rules}), "");
  EXPECT_EQ(live.scene().fuzzy_material->rules, rules);
  EXPECT_EQ(live.scene().fuzzy_material->rules_path, gone);
}

}  // namespace
}  // namespace neurocloth

namespace neurocloth {
namespace {

// The Learning panel's Apply: the weights ramp to the fitted material, whose
// viscosity replaces the user's; a later input change asks the rule base again.
TEST(LiveScene, AFittedMaterialRampsInAndReplacesTheUsersViscosity) {
  const Scene scene = test::asset_scene("hanging_fuzzy");
  LiveScene live(scene);
  EXPECT_EQ(live.apply(SetParameter{test::parameter("viscosity"), 0.3}), "");
  Material fitted = scene.material;
  fitted.spring_constant = 321;
  fitted.viscosity = 0.07;
  EXPECT_EQ(live.apply(ApplyFit{fitted, {}, {}}), "");
  EXPECT_TRUE(live.simulation().ramping());
  for (int frame = 0; frame < 100 && live.simulation().ramping(); ++frame)
    live.simulation().advance(0.01);  // the ramp takes 64 accepted steps
  ASSERT_FALSE(live.simulation().ramping());
  Scene target_scene = scene;
  target_scene.material = fitted;
  target_scene.fuzzy_material.reset();
  const ClothNetwork target = target_scene.build_network();
  const ClothNetwork& net = live.simulation().network();
  EXPECT_EQ(net.springs.stiffness, target.springs.stiffness);
  EXPECT_TRUE(all_equal(net.springs.damping, 0.07));

  // An input asks the rule base again: the fit gives way.
  EXPECT_EQ(live.apply(SetParameter{test::parameter(scene, "input.mass"), 0.9}), "");
  for (int frame = 0; frame < 100 && live.simulation().ramping(); ++frame)
    live.simulation().advance(0.01);
  std::map<std::string, double> inputs = scene.fuzzy_material->inputs;
  inputs["mass"] = 0.9;
  target_scene.material = scene.fuzzy_material->rules->derive(inputs).material;
  EXPECT_EQ(live.simulation().network().springs.stiffness,
            target_scene.build_network().springs.stiffness);
}

// A fit of the inputs keeps the material in words: the inputs move, and the
// rule base gives the weights, as the sliders would.
TEST(LiveScene, FittedInputsMoveTheSlidersNotTheNumbers) {
  const Scene scene = test::asset_scene("hanging_fuzzy");
  LiveScene live(scene);
  const ParameterId elasticity = test::parameter(scene, "input.elasticity");
  EXPECT_EQ(live.apply(ApplyFit{scene.material, {}, {{elasticity, 0.6}}}), "");
  for (int frame = 0; frame < 100 && live.simulation().ramping(); ++frame)
    live.simulation().advance(0.01);
  std::map<std::string, double> inputs = scene.fuzzy_material->inputs;
  inputs["elasticity"] = 0.6;
  Scene target = scene;
  target.material = scene.fuzzy_material->rules->derive(inputs).material;
  EXPECT_EQ(live.simulation().network().springs.stiffness,
            target.build_network().springs.stiffness);
  EXPECT_NE(target.material.spring_constant, scene.material.spring_constant);
  SimulationStatus status;
  live.describe(status);
  const std::pair<std::string, double> shown("elasticity", 0.6);
  EXPECT_NE(std::find(status.material_inputs.begin(), status.material_inputs.end(), shown),
            status.material_inputs.end());
  // An input the scene does not have is refused, and nothing changes.
  EXPECT_TRUE(contains(live.apply(ApplyFit{scene.material, {}, {{ParameterId::input(9), 0.5}}}),
                       "no input"));
}

TEST(LiveScene, AFitIsRefusedWholeWhenAnyPartCannotBeTaken) {
  LiveScene flag(test::asset_scene("flag"));
  const std::vector<double> stiffness = flag.simulation().network().springs.stiffness;
  Material bad = flag.scene().material;
  bad.node_mass = std::nan("");
  EXPECT_TRUE(contains(flag.apply(ApplyFit{bad, {}, {}}), "not finite"));
  bad.node_mass = -1;
  EXPECT_TRUE(contains(flag.apply(ApplyFit{bad, {}, {}}), "ApplyFit: the fitted material has"));

  Material good = flag.scene().material;
  good.spring_constant *= 2;
  const ParameterId wind_x = test::parameter(flag.scene(), "wind.velocity.x");
  EXPECT_TRUE(contains(flag.apply(ApplyFit{good, {{wind_x, std::nan("")}}, {}}), "not finite"));
  EXPECT_TRUE(contains(
      flag.apply(ApplyFit{good, {{ParameterId::module(7, ModuleParameter::rate, -1), 1.0}}, {}}),
      "no module parameter"));
  EXPECT_FALSE(flag.simulation().ramping());
  EXPECT_EQ(flag.simulation().network().springs.stiffness, stiffness);

  // A collider's friction is fitted, but the running cloth cannot take it.
  LiveScene table(test::asset_scene("table_drape"));
  const ParameterId box_friction = ParameterId::module(0, ModuleParameter::friction, -1);
  EXPECT_TRUE(contains(table.apply(ApplyFit{table.scene().material, {{box_friction, 0.3}}, {}}),
                       "cannot change while the cloth runs"));
  EXPECT_FALSE(table.simulation().ramping());

  // A fitted wind reaches the module and the status.
  EXPECT_EQ(flag.apply(ApplyFit{good, {{wind_x, -3.0}}, {}}), "");
  SimulationStatus s;
  flag.describe(s);
  EXPECT_EQ(*s.wind, Vec3(-3, 0, 0.8));
  EXPECT_TRUE(flag.simulation().ramping());
}

}  // namespace
}  // namespace neurocloth
