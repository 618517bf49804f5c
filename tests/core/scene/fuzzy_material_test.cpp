// Linguistic materials into the network: the shipped rule base, presets,
// scenes, and live changes.
#include "core/scene/fuzzy_material.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <map>
#include <string>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/formats/fcl_writer.h"
#include "core/fuzzy/term_degrees.h"
#include "core/io/input_error.h"
#include "core/simulation/relaxation.h"
#include "support/scene_builder.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

Material preset(const std::string& name) {
  const LinguisticMaterial lm = load_preset(name);
  return FuzzyMaterial::load(lm.rules_path).derive(lm.inputs).material;
}

TEST(FuzzyMaterial, ShippedRuleBaseHasThePapersDomainsAndRules) {
  const fuzzy::FuzzySystem s = fuzzy::read_fcl(assets_directory() + "/materials/cloth.fcl");
  for (const char* in : {"mass", "elasticity", "force"})
    EXPECT_GE(s.input_index(in), 0) << in;
  for (const char* out : FuzzyMaterial::kOutputs)
    EXPECT_GE(s.output_index(out), 0) << out;
  // The paper's three sample rules, in its words.
  const fuzzy::RuleBlock& paper = s.blocks.at(0);
  ASSERT_EQ(paper.rules.size(), 3u);
  const int mass = s.input_index("mass"), elasticity = s.input_index("elasticity"),
            force = s.input_index("force");
  const int k = s.output_index("spring_constant"), visc = s.output_index("viscosity");
  const auto& r1 = paper.rules[0];
  ASSERT_EQ(r1.condition.kind, fuzzy::Condition::Kind::all);
  EXPECT_EQ(r1.condition.children[0].variable, mass);
  EXPECT_EQ(s.inputs[mass].terms[r1.condition.children[0].term].name, "big");
  EXPECT_EQ(r1.condition.children[1].variable, elasticity);
  EXPECT_EQ(s.outputs[k].terms[r1.consequents[0].term].name, "low");
  EXPECT_EQ(paper.rules[1].condition.variable, mass);
  EXPECT_EQ(paper.rules[2].condition.variable, force);
  for (const auto& r : {paper.rules[1], paper.rules[2]}) {
    ASSERT_EQ(r.consequents.size(), 2u);
    EXPECT_EQ(s.outputs[k].terms[r.consequents[0].term].name, "low");  // "very low": a hedge
    EXPECT_EQ(r.consequents[0].hedges, std::vector<fuzzy::Hedge>{fuzzy::Hedge::very});
    EXPECT_EQ(r.consequents[1].variable, visc);
    EXPECT_EQ(s.outputs[visc].terms[r.consequents[1].term].name, "high");
  }
}

// The shipped file survives write -> read: same text again, same outputs.
// What a fit of the inputs prints: the terms a value belongs to, by degree.
TEST(FuzzyMaterial, AnInputIsSaidInTheRuleBasesWords) {
  const FuzzyMaterial m = FuzzyMaterial::load(assets_directory() + "/materials/cloth.fcl");
  const fuzzy::LinguisticVariable& e = m.system().inputs[1];
  ASSERT_EQ(e.name, "elasticity");
  EXPECT_EQ(fuzzy::in_words(e, 0.3), "elasticity 0.3: medium 0.80, small 0.20");
  EXPECT_EQ(fuzzy::in_words(e, 0.05), "elasticity 0.05: small 1.00");
  const auto degrees = fuzzy::term_degrees(e, 0.5);  // medium 0.5, big (0.5-0.35)/0.45
  ASSERT_EQ(degrees.size(), 2u);
  EXPECT_EQ(degrees[0].term, "medium");
  EXPECT_DOUBLE_EQ(degrees[0].degree, 0.5);
  EXPECT_EQ(degrees[1].term, "big");
  EXPECT_DOUBLE_EQ(degrees[1].degree, 0.15 / 0.45);
  // Outside its range a value is read where inference reads it: clamped.
  EXPECT_EQ(fuzzy::in_words(e, 7.0), "elasticity 7: big 1.00");
  fuzzy::LinguisticVariable gap = e;
  gap.terms.resize(1);  // small only: 0.5 belongs to no term
  EXPECT_EQ(fuzzy::in_words(gap, 0.5), "elasticity 0.5: no term");
}

TEST(FuzzyMaterial, ShippedRuleBaseRoundTripsThroughTheWriter) {
  const fuzzy::FuzzySystem s = fuzzy::read_fcl(assets_directory() + "/materials/cloth.fcl");
  const std::string text = fuzzy::write_fcl(s);
  const fuzzy::FuzzySystem back = fuzzy::parse_fcl(text, "written.fcl");
  EXPECT_EQ(fuzzy::write_fcl(back), text);
  for (const auto& name : {"silk", "cotton", "denim", "leather", "rubber"}) {
    const LinguisticMaterial lm = load_preset(name);
    const Material a = FuzzyMaterial(s, "a").derive(lm.inputs).material;
    const Material b = FuzzyMaterial(back, "b").derive(lm.inputs).material;
    EXPECT_EQ(a.spring_constant, b.spring_constant) << name;
    EXPECT_EQ(a.node_mass, b.node_mass) << name;
    EXPECT_EQ(a.viscosity, b.viscosity) << name;
    EXPECT_EQ(a.friction, b.friction) << name;
    EXPECT_EQ(a.bend_constant, b.bend_constant) << name;
  }
}

// Every output has a rule firing for any input in range: no defaults used on a
// 9 x 9 x 9 grid over the input space.
TEST(FuzzyMaterial, ShippedRulesCoverTheInputSpace) {
  const FuzzyMaterial m = FuzzyMaterial::load(assets_directory() + "/materials/cloth.fcl");
  const auto& in = m.system().inputs;
  for (int a = 0; a <= 8; ++a)
    for (int b = 0; b <= 8; ++b)
      for (int c = 0; c <= 8; ++c) {
        auto at = [&](int v, int i) { return in[v].min + (in[v].max - in[v].min) * i / 8.0; };
        const DerivedMaterial d =
            m.derive({{"mass", at(0, a)}, {"elasticity", at(1, b)}, {"force", at(2, c)}});
        for (bool defaulted : d.report.defaulted)
          ASSERT_FALSE(defaulted) << a << " " << b << " " << c;
        EXPECT_GT(d.material.node_mass, 0);
        EXPECT_GE(d.material.spring_constant, 0);
      }
}

// Sanity against Blender's cloth presets (structural stiffness silk 5 < cotton
// 15 < denim 40 < leather 80; mass silk 0.15 < cotton 0.3 < rubber 3) and
// measured fabric densities (0.15-0.35 kg/m^2 for ordinary fabrics).
TEST(FuzzyMaterial, PresetsComeOutInASensibleOrder) {
  const Material silk = preset("silk"), cotton = preset("cotton"), denim = preset("denim"),
                 leather = preset("leather"), rubber = preset("rubber");
  EXPECT_LT(silk.spring_constant, cotton.spring_constant);
  EXPECT_LT(cotton.spring_constant, denim.spring_constant);
  EXPECT_LT(denim.spring_constant, leather.spring_constant);
  EXPECT_GT(leather.spring_constant, 3 * silk.spring_constant);
  EXPECT_LT(rubber.spring_constant, cotton.spring_constant);  // "very elastic"
  EXPECT_LT(silk.node_mass, cotton.node_mass);
  EXPECT_LT(cotton.node_mass, denim.node_mass);
  EXPECT_GT(rubber.node_mass, silk.node_mass);
  EXPECT_GT(rubber.node_mass, leather.node_mass);
  // cotton at 0.2 kg/m^2 on a 5 cm grid: 0.0005 kg a node.
  EXPECT_NEAR(cotton.node_mass / 0.0025, 0.2, 1e-9);
  EXPECT_GT(rubber.friction, cotton.friction);
  EXPECT_LT(silk.friction, cotton.friction);
}

// shear_constant and bend_constant are optional outputs: a rule base without
// them leaves shear and bend springs at the spring constant, one with them sets
// them, and their ranges are checked like the others'.
TEST(FuzzyMaterial, ShearAndBendOutputsAreOptional) {
  const fuzzy::FuzzySystem shipped = fuzzy::read_fcl(assets_directory() + "/materials/cloth.fcl");
  const std::map<std::string, double> inputs = {{"mass", 0.4}, {"elasticity", 0.2}, {"force", 6}};
  const Material with = FuzzyMaterial(shipped, "with").derive(inputs).material;
  const int bend = shipped.output_index("bend_constant");
  ASSERT_GE(bend, 0);
  EXPECT_GT(with.bend_constant, shipped.outputs[bend].min);
  EXPECT_LT(with.bend_constant, 0.5 * with.spring_constant);  // cloth bends more easily
  EXPECT_EQ(with.shear(), with.spring_constant);

  // The same rule base written without bend_constant (its output and the rules that set it).
  std::string text = fuzzy::write_fcl(shipped);
  const auto cut = [&](const std::string& from, const std::string& to) {
    const std::size_t a = text.find(from);
    ASSERT_NE(a, std::string::npos) << from;
    const std::size_t b = text.find(to, a);
    ASSERT_NE(b, std::string::npos) << to;
    text.erase(a, b + to.size() - a);
  };
  cut("bend_constant : REAL;", ";");
  cut("DEFUZZIFY bend_constant", "END_DEFUZZIFY");
  cut("RULEBLOCK bending", "END_RULEBLOCK");
  const fuzzy::FuzzySystem without_bend = fuzzy::parse_fcl(text, "without_bend.fcl");
  ASSERT_LT(without_bend.output_index("bend_constant"), 0);
  const Material without = FuzzyMaterial(without_bend, "without").derive(inputs).material;
  EXPECT_LT(without.bend_constant, 0);
  EXPECT_EQ(without.bend(), without.spring_constant);
  EXPECT_EQ(without.spring_constant, with.spring_constant);  // nothing else moves
  EXPECT_EQ(without.node_mass, with.node_mass);
  EXPECT_EQ(without.viscosity, with.viscosity);
  EXPECT_EQ(without.friction, with.friction);

  fuzzy::FuzzySystem negative = shipped;
  negative.outputs[bend].min = -1;
  try {
    FuzzyMaterial(negative, "negative.fcl");
    FAIL() << "a bend_constant range below 0 must be refused";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "negative.fcl");
    EXPECT_EQ(e.field(), "DEFUZZIFY bend_constant");
  }
}

TEST(FuzzyMaterial, PresetNamesAndErrors) {
  const auto names = preset_names();
  for (const char* n : {"silk", "cotton", "denim", "leather", "rubber"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
  EXPECT_THROW(load_preset("velvet"), InputError);
  const FuzzyMaterial m = FuzzyMaterial::load(assets_directory() + "/materials/cloth.fcl");
  try {
    m.derive({{"mass", 0.2}, {"elasticity", 0.3}}, "scene.json", "material.inputs");
    FAIL() << "a missing input must be an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "material.inputs.force");
    EXPECT_EQ(e.file(), "scene.json");
  }
  try {
    m.derive({{"mass", 0.2}, {"elasticity", 0.3}, {"force", 1}, {"colour", 2}}, "scene.json",
             "material.inputs");
    FAIL() << "an unknown input must be an error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "material.inputs.colour");
  }
}

TEST(FuzzyMaterial, OutOfRangeInputsAreClampedAndReported) {
  const FuzzyMaterial m = FuzzyMaterial::load(assets_directory() + "/materials/cloth.fcl");
  const DerivedMaterial d = m.derive({{"mass", 9.0}, {"elasticity", 0.3}, {"force", 3}});
  EXPECT_FALSE(d.report.notes.empty());
  EXPECT_NEAR(d.material.node_mass, 1.5 * 0.0025, 1e-12);  // clamped to the range's 1.5
}

TEST(FuzzyMaterial, SceneMaterialFromRulesSetsEveryWeight) {
  const Scene scene = test::asset_scene("hanging_fuzzy");
  ASSERT_TRUE(scene.fuzzy_material.has_value());
  const Material expected = FuzzyMaterial::load(scene.fuzzy_material->rules_path)
                                .derive(scene.fuzzy_material->inputs)
                                .material;
  // cloth.fcl has a bend_constant output (and no shear_constant): bend springs
  // take it, shear springs the spring constant.
  ASSERT_GE(expected.bend_constant, 0);
  ASSERT_LT(expected.shear_constant, 0);
  const ClothNetwork net = scene.build_network();
  int families[3] = {0, 0, 0};
  for (std::size_t s = 0; s < net.spring_count(); ++s) {
    const SpringFamily f = net.springs.family[s];
    ++families[static_cast<int>(f)];
    ASSERT_EQ(net.springs.stiffness[s],
              f == SpringFamily::bend ? expected.bend_constant : expected.spring_constant);
    ASSERT_EQ(net.springs.damping[s], expected.viscosity);
  }
  for (int count : families)
    EXPECT_GT(count, 0);
  for (std::size_t i = 0; i < net.node_count(); ++i)
    ASSERT_EQ(net.masses.friction[i], expected.friction);
  // node_mass is the mass of 0.0025 m^2 of cloth; each node carries its lumped
  // share: a whole one inside the 5 cm grid, half on an edge.
  EXPECT_NEAR(net.mass(5 * 20 + 5), expected.node_mass, 1e-12 * expected.node_mass);
  EXPECT_NEAR(net.mass(5 * 20 + 0), 0.5 * expected.node_mass, 1e-12 * expected.node_mass);
  // So the cloth weighs density x area (0.2 kg/m^2 x 0.95 m x 0.95 m) at any
  // resolution: the same cloth on a grid twice as fine.
  auto total = [](const ClothNetwork& n) {
    double m = 0;
    for (std::size_t i = 0; i < n.node_count(); ++i)
      m += n.mass(i);
    return m;
  };
  EXPECT_NEAR(total(net), 0.2 * 0.95 * 0.95, 1e-12);
  Scene fine = scene;
  GridSpec g = *fine.grid;
  g.rows = g.cols = 39;
  g.spacing = 0.025;
  fine.grid = g;
  fine.topology = build_grid(g);
  fine.pins = {0, 38};
  EXPECT_NEAR(total(fine.build_network()), 0.2 * 0.95 * 0.95, 1e-12);
  Simulation sim = scene.make_simulation();
  EXPECT_EQ(sim.advance(0.5), RunStatus::ok) << sim.divergence_reason();
}

TEST(FuzzyMaterial, ScenePresetAndBadMaterialsNameFileAndField) {
  const std::string path = std::string(NEUROCLOTH_TEST_TMP) + "/preset_scene.json";
  auto scene_of = [](const std::string& material) {
    return test::SceneBuilder(3, 3, 0.1).set("/material", nlohmann::json::parse(material)).text();
  };
  const Scene s = parse_scene(scene_of(R"({"preset": "leather"})"), path);
  EXPECT_NEAR(s.material.spring_constant, preset("leather").spring_constant, 1e-12);
  auto error_field = [&](const std::string& material) {
    try {
      parse_scene(scene_of(material), path);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      return e.field();
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_field(R"({"preset": "velvet"})"), "material.preset");
  EXPECT_EQ(error_field(R"({"rules": "materials/cloth.fcl", "inputs": {"mass": 0.2}})"),
            "material.inputs.elasticity");
  EXPECT_EQ(
      error_field(
          R"({"rules": "materials/cloth.fcl", "inputs": {"mass": "heavy", "elasticity": 0, "force": 0}})"),
      "material.inputs.mass");
  EXPECT_EQ(error_field(R"({"rules": "materials/cloth.fcl"})"), "material.inputs");
}

// A live change of a linguistic input: re-derived and ramped in over a few
// steps. A jolt is a sudden change of acceleration, so it is measured as the
// largest one-step change of any node's acceleration (the second difference of
// its velocity), against applying the new weights at once.
// Runs `before` quiet steps, calls change(), runs `after` more; returns the
// largest one-step change of acceleration over the steps after the change
// (the step where it lands included) and, in `quiet`, over the ones before.
template <class Change>
double largest_jerk(Simulation& sim, int before, int after, Change&& change, double& quiet) {
  const double dt = sim.settings().dt;
  quiet = 0;
  double worst = 0;
  std::vector<Vec3> acc_before;
  for (int i = 0; i < before + after; ++i) {
    if (i == before) change();
    const ClothState previous = sim.state();
    sim.advance(dt);
    std::vector<Vec3> acc(previous.size());
    for (std::size_t n = 0; n < acc.size(); ++n)
      acc[n] = (sim.state().velocity(n) - previous.velocity(n)) / dt;
    if (!acc_before.empty())
      for (std::size_t n = 0; n < acc.size(); ++n)
        (i < before ? quiet : worst) =
            std::max(i < before ? quiet : worst, (acc[n] - acc_before[n]).norm());
    acc_before = acc;
  }
  return worst;
}

TEST(FuzzyMaterial, LiveChangeIsRampedWithoutAJolt) {
  Scene scene = test::asset_scene("hanging_fuzzy");
  scene.solver.adaptive = false;
  scene.solver.dt = 5e-5;
  const FuzzyMaterial rules = FuzzyMaterial::load(scene.fuzzy_material->rules_path);
  auto inputs = scene.fuzzy_material->inputs;  // cotton-like ...
  inputs["elasticity"] = 0.05;                 // ... to leather-like: stiff,
  inputs["mass"] = 0.8;                        // heavy,
  inputs["force"] = 8;                         // and made to carry loads
  const Material target = rules.derive(inputs).material;
  ASSERT_GT(target.spring_constant, 1.5 * scene.material.spring_constant);

  // From the static drape, so that the only event is the change.
  const ClothNetwork net = scene.build_network();
  ClothState drape = scene.initial_state();
  ASSERT_TRUE(relax(net, drape).converged);
  Simulation ramped(net, drape, scene.solver), instant(net, drape, scene.solver);
  double quiet = 0, quiet_instant = 0;
  const double jerk_ramped = largest_jerk(
      ramped, 10, 100, [&] { ramped.ramp_to_material(target, 64); }, quiet);
  const double jerk_instant = largest_jerk(
      instant, 10, 100, [&] { instant.mutable_network().apply_material(target); }, quiet_instant);
  std::cout << "largest one-step acceleration change, m/s^2: at once " << jerk_instant
            << ", ramped " << jerk_ramped << ", before the change " << quiet << "\n";
  EXPECT_FALSE(ramped.ramping());
  EXPECT_EQ(ramped.network().springs.stiffness[7], target.spring_constant);  // landed exactly
  EXPECT_EQ(ramped.network().masses.inverse_mass[7],
            1.0 / (target.node_mass * ramped.network().mass_share[7]));
  EXPECT_GT(jerk_instant, 100 * quiet);  // the change really is a jolt when applied at once
  EXPECT_LT(jerk_ramped, 0.1 * jerk_instant) << "quiet " << quiet;
  EXPECT_EQ(ramped.status(), RunStatus::ok);
}

}  // namespace
}  // namespace neurocloth
