// The inference engine against hand-computed cases, brute-force integration
// and finite differences.
#include "core/fuzzy/inference.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/formats/fcl_writer.h"
#include "core/io/asset_paths.h"
#include "support/fuzzy_builders.h"

namespace neurocloth::fuzzy {
namespace {
using namespace test;

// x in [0, 10] with A = trian 0 5 10; y in [0, 10] with B1 = trian 0 2 4 and
// B2 = trian 4 8 10. Rules: IF x IS A THEN y IS B1; IF x IS NOT A THEN y IS B2.
FuzzySystem two_rule_mamdani(Activation act) {
  FuzzySystem s;
  s.inputs = {variable("x", 0, 10, {{"A", mf(Shape::triangle, {0, 5, 10})}})};
  s.outputs = {
      variable("y", 0, 10,
               {{"B1", mf(Shape::triangle, {0, 2, 4})}, {"B2", mf(Shape::triangle, {4, 8, 10})}})};
  RuleBlock b;
  b.activation = act;
  b.rules = {rule(is(0, 0), 0, 0), rule(is(0, 0, {}, true), 0, 1)};
  s.blocks = {b};
  return s;
}

TEST(Inference, MamdaniCentroidByHandMinActivation) {
  // x = 2.5: A = 0.5, NOT A = 0.5.
  // B1 clipped at 0.5: (0,0) (1,.5) (3,.5) (4,0): area 1.5, centroid 2 -> moment 3.
  // B2 clipped at 0.5: (4,0) (6,.5) (9,.5) (10,0): pieces [4,6] area .5 moment 8/3,
  //   [6,9] area 1.5 moment 11.25, [9,10] area .25 moment 7/3: area 2.25, moment 16.25.
  // Centroid (3 + 16.25) / (1.5 + 2.25) = 19.25 / 3.75 = 77/15.
  const InferenceReport r = infer(two_rule_mamdani(Activation::min), {2.5});
  EXPECT_NEAR(r.outputs[0], 77.0 / 15.0, 1e-12);
  EXPECT_DOUBLE_EQ(r.activation[0][0], 0.5);
  EXPECT_DOUBLE_EQ(r.activation[0][1], 0.5);
  EXPECT_FALSE(r.defaulted[0]);
}

TEST(Inference, MamdaniCentroidByHandProductActivation) {
  // 0.5 * B1: area 1, centroid 2 -> moment 2; 0.5 * B2: area 1.5, centroid
  // (4 + 8 + 10) / 3 = 22/3 -> moment 11. Centroid 13 / 2.5 = 5.2.
  const InferenceReport r = infer(two_rule_mamdani(Activation::product), {2.5});
  EXPECT_NEAR(r.outputs[0], 5.2, 1e-12);
}

// x in [0, 10], lo = trian 0 0 10, hi = trian 0 10 10; Sugeno output z with
// c = singleton 2 and lin = 1 + 0.5 x.
FuzzySystem sugeno() {
  FuzzySystem s;
  s.inputs = {variable(
      "x", 0, 10,
      {{"lo", mf(Shape::triangle, {0, 0, 10})}, {"hi", mf(Shape::triangle, {0, 10, 10})}})};
  LinguisticVariable z = variable(
      "z", 0, 10, {{"c", mf(Shape::singleton, {2})}, {"lin", mf(Shape::linear, {1, 0.5})}});
  z.method = Defuzzification::weighted_average;
  s.outputs = {z};
  RuleBlock b;
  b.rules = {rule(is(0, 0), 0, 0), rule(is(0, 1), 0, 1)};
  s.blocks = {b};
  return s;
}

TEST(Inference, TakagiSugenoByHand) {
  // x = 4: lo = 0.6, hi = 0.4; z = (0.6 * 2 + 0.4 * (1 + 0.5 * 4)) / (0.6 + 0.4) = 2.4.
  EXPECT_NEAR(infer(sugeno(), {4}).outputs[0], 2.4, 1e-14);
  // Rule weights scale the activations: WITH 0.5 on the first rule:
  // (0.3 * 2 + 0.4 * 3) / 0.7 = 1.8 / 0.7.
  FuzzySystem s = sugeno();
  s.blocks[0].rules[0].weight = 0.5;
  EXPECT_NEAR(infer(s, {4}).outputs[0], 1.8 / 0.7, 1e-14);
}

TEST(Inference, HedgesNegationAndOperators) {
  FuzzySystem s = sugeno();
  auto degree = [&](Condition c, AndMethod a = AndMethod::min, OrMethod o = OrMethod::max) {
    s.blocks[0].rules = {rule(std::move(c), 0, 0)};
    s.blocks[0].and_method = a;
    s.blocks[0].or_method = o;
    return infer(s, {4}).activation[0][0];  // lo = 0.6, hi = 0.4
  };
  EXPECT_NEAR(degree(is(0, 0, {Hedge::very})), 0.36, 1e-15);
  EXPECT_NEAR(degree(is(0, 1, {Hedge::somewhat})), std::sqrt(0.4), 1e-15);
  EXPECT_NEAR(degree(is(0, 0, {}, true)), 0.4, 1e-15);
  // "very somewhat lo" = very(somewhat(0.6)) = 0.6.
  EXPECT_NEAR(degree(is(0, 0, {Hedge::very, Hedge::somewhat})), 0.6, 1e-15);
  // "IS NOT very lo" = 1 - 0.36.
  EXPECT_NEAR(degree(is(0, 0, {Hedge::very}, true)), 0.64, 1e-15);
  using K = Condition::Kind;
  EXPECT_NEAR(degree(combine(K::all, {is(0, 0), is(0, 1)})), 0.4, 1e-15);
  EXPECT_NEAR(degree(combine(K::all, {is(0, 0), is(0, 1)}), AndMethod::product), 0.24, 1e-15);
  EXPECT_NEAR(degree(combine(K::any, {is(0, 0), is(0, 1)})), 0.6, 1e-15);
  EXPECT_NEAR(
      degree(combine(K::any, {is(0, 0), is(0, 1)}), AndMethod::min, OrMethod::probabilistic_sum),
      0.6 + 0.4 - 0.24, 1e-15);
  EXPECT_NEAR(degree(combine(K::negation, {combine(K::all, {is(0, 0), is(0, 1)})})), 0.6, 1e-15);
}

// Overlapping output sets under ACCU MAX cross each other: the exact centroid
// must find the crossings. Checked against a brute-force midpoint rule.
double brute_force_centroid(const FuzzySystem& s, const InferenceReport& r, int n = 2000000) {
  const LinguisticVariable& v = s.outputs[0];
  const RuleBlock& b = s.blocks[0];
  double area = 0, moment = 0;
  const double h = (v.max - v.min) / n;
  for (int i = 0; i < n; ++i) {
    const double y = v.min + (i + 0.5) * h;
    double a = 0;
    for (std::size_t k = 0; k < b.rules.size(); ++k) {
      const Consequent& c = b.rules[k].consequents[0];
      double m = v.terms[c.term].function(y);
      for (auto h = c.hedges.rbegin(); h != c.hedges.rend(); ++h)
        m = *h == Hedge::very ? m * m : std::sqrt(m);
      if (c.negated) m = 1 - m;
      const double alpha = r.activation[0][k];
      const double implied = b.activation == Activation::min ? std::min(alpha, m) : alpha * m;
      a = b.accumulation == Accumulation::max ? std::max(a, implied) : a + implied;
    }
    area += a * h;
    moment += a * y * h;
  }
  return moment / area;
}

TEST(Inference, ExactCentroidAgreesWithBruteForce) {
  for (Activation act : {Activation::min, Activation::product})
    for (Accumulation accu : {Accumulation::max, Accumulation::sum}) {
      FuzzySystem s;
      s.inputs = {variable("x", 0, 1,
                           {{"a", mf(Shape::triangle, {0, 0.3, 1})},
                            {"b", mf(Shape::trapezoid, {0, 0.5, 0.7, 1})},
                            {"c", mf(Shape::points, {0, 1, 0.4, 0.2, 1, 0})}})};
      s.outputs = {variable("y", -2, 3,
                            {{"p", mf(Shape::triangle, {-2, -0.5, 1.5})},
                             {"q", mf(Shape::trapezoid, {-1, 0, 1, 2.5})},
                             {"r", mf(Shape::points, {0, 0, 1, 1, 2, 0.3, 3, 0.8})}})};
      RuleBlock b;
      b.activation = act;
      b.accumulation = accu;
      b.rules = {rule(is(0, 0), 0, 0), rule(is(0, 1), 0, 1), rule(is(0, 2), 0, 2)};
      s.blocks = {b};
      for (double x : {0.1, 0.35, 0.6, 0.9}) {
        const InferenceReport r = infer(s, {x});
        EXPECT_NEAR(r.outputs[0], brute_force_centroid(s, r), 1e-9) << "x " << x;
      }
    }
}

TEST(Inference, SampledCentroidForSmoothSetsIsAccurateTo1e6) {
  FuzzySystem s;
  s.inputs = {variable(
      "x", 0, 1, {{"a", mf(Shape::sigmoid, {8, 0.4})}, {"b", mf(Shape::bell, {0.2, 2, 0.6})}})};
  s.outputs = {variable(
      "y", 0, 10, {{"p", mf(Shape::gaussian, {3, 1.2})}, {"q", mf(Shape::bell, {1.5, 3, 7})}})};
  RuleBlock b;
  b.rules = {rule(is(0, 0), 0, 0), rule(is(0, 1), 0, 1)};
  s.blocks = {b};
  for (double x : {0.2, 0.5, 0.8}) {
    const InferenceReport r = infer(s, {x});
    EXPECT_NEAR(r.outputs[0], brute_force_centroid(s, r, 200000), 1e-6 * 10) << "x " << x;
  }
}

// "THEN y IS very B2", "THEN y IS NOT B1": hedges and NOT shape the output set.
TEST(Inference, ConsequentHedgesShapeTheOutputSet) {
  const std::string text = R"(FUNCTION_BLOCK h
VAR_INPUT x : REAL; END_VAR
VAR_OUTPUT y : REAL; END_VAR
FUZZIFY x RANGE := (0 .. 10); TERM A := TRIAN 0 5 10; END_FUZZIFY
DEFUZZIFY y RANGE := (0 .. 10); TERM B1 := TRIAN 0 2 4; TERM B2 := TRIAN 4 8 10; METHOD : COG; END_DEFUZZIFY
RULEBLOCK r
  RULE 1 : IF x IS A THEN y IS NOT B1;
  RULE 2 : IF x IS NOT A THEN y IS very B2;
END_RULEBLOCK
END_FUNCTION_BLOCK)";
  const FuzzySystem s = parse_fcl(text, "hedges.fcl");
  const Consequent& c1 = s.blocks[0].rules[0].consequents[0];
  const Consequent& c2 = s.blocks[0].rules[1].consequents[0];
  EXPECT_TRUE(c1.negated);
  EXPECT_EQ(c2.hedges, (std::vector<Hedge>{Hedge::very}));
  EXPECT_EQ(write_fcl(parse_fcl(write_fcl(s), "again.fcl")), write_fcl(s));  // round trip
  for (double x : {1.0, 2.5, 4.0}) {
    const InferenceReport r = infer(s, {x});
    EXPECT_NEAR(r.outputs[0], brute_force_centroid(s, r), 1e-6) << "x " << x;
  }
  // NOT keeps the sets piecewise linear: exact. Without the hedge the answer
  // differs (at x = 1, where B2 is clipped at 0.8, above NOT B1's 0.2).
  FuzzySystem plain = s;
  plain.blocks[0].rules[1].consequents[0].hedges.clear();
  const InferenceReport r = infer(plain, {1.0});
  EXPECT_NEAR(r.outputs[0], brute_force_centroid(plain, r), 1e-9);
  EXPECT_GT(std::abs(r.outputs[0] - infer(s, {1.0}).outputs[0]), 1e-2);
}

TEST(Inference, InputsOutsideTheRangeAreClampedAndReported) {
  const InferenceReport r = infer(sugeno(), {14});
  EXPECT_TRUE(r.clamped[0]);
  EXPECT_NEAR(r.outputs[0], infer(sugeno(), {10}).outputs[0], 1e-15);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_NE(r.notes[0].find("clamped to 10"), std::string::npos) << r.notes[0];
}

TEST(Inference, NoRuleFiringKeepsTheDefaultInsteadOfNaN) {
  FuzzySystem s = two_rule_mamdani(Activation::min);
  s.blocks[0].rules.pop_back();  // only "IF x IS A", and A is 0 at x = 0
  s.outputs[0].default_value = 7.5;
  InferenceReport r = infer(s, {0});
  EXPECT_TRUE(r.defaulted[0]);
  EXPECT_EQ(r.outputs[0], 7.5);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_NE(r.notes.back().find("no rule fired for output 'y'"), std::string::npos);
  s.outputs[0].default_value = std::nan("");
  r = infer(s, {0});
  EXPECT_EQ(r.outputs[0], 5.0);  // the documented fallback: the range's midpoint
}

// Every derivative against a central finite difference, at points away from
// kinks, for a Mamdani (exact and sampled) and a Sugeno system.
void check_gradient(FuzzySystem s, const std::vector<double>& x, double tol) {
  const InferenceGradient g = infer_gradient(s, x);
  const InferenceReport plain = infer(s, x);
  for (std::size_t o = 0; o < plain.outputs.size(); ++o)
    EXPECT_EQ(g.report.outputs[o], plain.outputs[o]);
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double h = 1e-6;
    auto xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    const double fd = (infer(s, xp).outputs[0] - infer(s, xm).outputs[0]) / (2 * h);
    EXPECT_NEAR(g.d_inputs(0, i), fd, tol * std::max(1.0, std::abs(fd))) << "input " << i;
  }
  for (std::size_t k = 0; k < g.parameters.size(); ++k) {
    const double v = get_parameter(s, g.parameters[k]), h = 1e-6 * std::max(1.0, std::abs(v));
    FuzzySystem sp = s, sm = s;
    set_parameter(sp, g.parameters[k], v + h);
    set_parameter(sm, g.parameters[k], v - h);
    const double fd = (infer(sp, x).outputs[0] - infer(sm, x).outputs[0]) / (2 * h);
    EXPECT_NEAR(g.d_parameters(0, k), fd, tol * std::max(1.0, std::abs(fd)))
        << g.parameters[k].name;
  }
}

TEST(Inference, DerivativesMatchFiniteDifferences) {
  for (Activation act : {Activation::min, Activation::product}) {
    // B2's right corner sits on the range's edge, where the centroid has a
    // kink (a central difference straddles it); move it inside.
    FuzzySystem s = two_rule_mamdani(act);
    s.outputs[0].terms[1].function.params[2] = 9.5;
    check_gradient(s, {act == Activation::min ? 2.7 : 3.1}, 1e-6);
  }
  check_gradient(sugeno(), {3.3}, 1e-7);
  FuzzySystem smooth;
  smooth.inputs = {variable(
      "x", 0, 1, {{"a", mf(Shape::sigmoid, {8, 0.4})}, {"b", mf(Shape::gaussian, {0.6, 0.2})}})};
  smooth.outputs = {variable(
      "y", 0, 10, {{"p", mf(Shape::gaussian, {3, 1.2})}, {"q", mf(Shape::bell, {1.5, 3, 7})}})};
  RuleBlock b;
  b.activation = Activation::product;
  b.accumulation = Accumulation::sum;
  b.rules = {rule(is(0, 0, {Hedge::very}), 0, 0, 0.9), rule(is(0, 1, {Hedge::somewhat}), 0, 1)};
  smooth.blocks = {b};
  check_gradient(smooth, {0.45}, 1e-5);
}

// Derivatives with respect to chosen parameters are the matching columns of
// the full ones, whichever order and subset is asked for; and all seeds carried
// at once give what one seed at a time gives (each run then carries a single
// derivative, so no two seeds' lists are ever merged: an independent check of
// the sparse arithmetic in dual.h).
bool same(double a, double b) {
  return std::abs(a - b) <= 1e-12 * std::max({std::abs(a), std::abs(b), 1e-300});
}

void check_seeds(const FuzzySystem& s, const std::vector<double>& x) {
  const InferenceGradient full = infer_gradient(s, x);
  const std::size_t np = full.parameters.size();
  ASSERT_EQ(full.d_parameters.cols(), Eigen::Index(np));
  // Every third parameter, last first.
  std::vector<Parameter> some;
  std::vector<std::size_t> column;
  for (std::size_t k = np; k-- > 0;)
    if (k % 3 == 1) some.push_back(full.parameters[k]), column.push_back(k);
  const InferenceGradient part = infer_gradient(s, x, some);
  const InferenceGradient inputs_only = infer_gradient(s, x, {});
  ASSERT_EQ(part.d_parameters.cols(), Eigen::Index(some.size()));
  EXPECT_EQ(inputs_only.d_parameters.cols(), 0);
  for (Eigen::Index o = 0; o < full.d_inputs.rows(); ++o) {
    EXPECT_EQ(part.report.outputs[o], full.report.outputs[o]);
    for (Eigen::Index i = 0; i < full.d_inputs.cols(); ++i) {
      EXPECT_PRED2(same, part.d_inputs(o, i), full.d_inputs(o, i)) << "output " << o;
      EXPECT_PRED2(same, inputs_only.d_inputs(o, i), full.d_inputs(o, i)) << "output " << o;
    }
    for (std::size_t j = 0; j < some.size(); ++j)
      EXPECT_PRED2(same, part.d_parameters(o, Eigen::Index(j)),
                   full.d_parameters(o, Eigen::Index(column[j])))
          << some[j].name;
  }
  double largest = 0;  // the comparison means something only if derivatives are nonzero
  for (std::size_t k = 0; k < np; ++k) {
    const InferenceGradient one = infer_gradient(s, x, {full.parameters[k]});
    for (Eigen::Index o = 0; o < full.d_inputs.rows(); ++o) {
      EXPECT_PRED2(same, one.d_parameters(o, 0), full.d_parameters(o, Eigen::Index(k)))
          << full.parameters[k].name << " output " << o;
      largest = std::max(largest, std::abs(one.d_parameters(o, 0)));
    }
  }
  EXPECT_GT(largest, 0.0);
}

TEST(Inference, ChosenSeedsGiveTheSameDerivativesAsAllSeeds) {
  for (Activation act : {Activation::min, Activation::product})
    check_seeds(two_rule_mamdani(act), {2.7});
  check_seeds(sugeno(), {3.3});
  const FuzzySystem cloth = read_fcl(assets_directory() + "/materials/cloth.fcl");
  for (const std::vector<double>& x :
       {std::vector<double>{0.2, 0.5, 3.0}, {0.05, 0.2, 8.0}, {0.9, 0.77, 6.1}})
    check_seeds(cloth, x);
}

TEST(Inference, GradientRefusesUnknownAndRepeatedParameters) {
  const FuzzySystem s = sugeno();
  const Parameter p = parameters(s)[0];
  EXPECT_THROW(infer_gradient(s, {3.3}, {p, p}), std::invalid_argument);
  Parameter missing = p;
  missing.term = 7;
  EXPECT_THROW(infer_gradient(s, {3.3}, {missing}), std::invalid_argument);
}

// Under ACCU MAX the engine finds the winning implied set on plain numbers
// and differentiates only it. Checked against the max taken over duals: the
// same system with one more block, ACCU SUM, whose rule cannot fire (its input
// sits where its term is flat at 0) takes the general path, and adding its
// zero changes no value and no derivative.
FuzzySystem with_idle_sum_block(FuzzySystem s) {
  s.inputs.push_back(variable("idle", 0, 10, {{"far", mf(Shape::triangle, {5, 6, 7})}}));
  RuleBlock idle;
  idle.name = "idle";
  idle.accumulation = Accumulation::sum;
  idle.activation = s.blocks[0].activation;
  for (std::size_t o = 0; o < s.outputs.size(); ++o)
    if (s.outputs[o].method == Defuzzification::centroid)
      idle.rules.push_back(rule(is(int(s.inputs.size()) - 1, 0), int(o), 0));
  s.blocks.push_back(idle);
  return s;
}

void check_max_shortcut(const FuzzySystem& s, std::vector<double> x) {
  const std::vector<Parameter> wrt = parameters(s);
  const InferenceGradient shortcut = infer_gradient(s, x, wrt);
  x.push_back(1.0);  // "idle" is 0 there, with no slope
  const InferenceGradient general = infer_gradient(with_idle_sum_block(s), x, wrt);
  double largest = 0;
  for (Eigen::Index o = 0; o < shortcut.d_inputs.rows(); ++o) {
    EXPECT_EQ(general.report.outputs[o], shortcut.report.outputs[o]);
    for (Eigen::Index i = 0; i < shortcut.d_inputs.cols(); ++i)
      EXPECT_PRED2(same, general.d_inputs(o, i), shortcut.d_inputs(o, i)) << "output " << o;
    for (std::size_t k = 0; k < wrt.size(); ++k) {
      EXPECT_PRED2(same, general.d_parameters(o, Eigen::Index(k)),
                   shortcut.d_parameters(o, Eigen::Index(k)))
          << wrt[k].name << " output " << o;
      largest = std::max(largest, std::abs(shortcut.d_parameters(o, Eigen::Index(k))));
    }
  }
  EXPECT_GT(largest, 0.0);
}

TEST(Inference, AccuMaxShortcutEqualsTheMaxOverDuals) {
  for (Activation act : {Activation::min, Activation::product})
    check_max_shortcut(two_rule_mamdani(act), {2.7});
  // Sampled: a consequent hedge makes the output set curved.
  FuzzySystem hedged = two_rule_mamdani(Activation::min);
  hedged.blocks[0].rules[1].consequents[0].hedges = {Hedge::very};
  check_max_shortcut(hedged, {3.1});
  // cloth.fcl: spring_constant sampled ("very low"), viscosity and friction exact.
  const FuzzySystem cloth = read_fcl(assets_directory() + "/materials/cloth.fcl");
  for (const std::vector<double>& x :
       {std::vector<double>{0.2, 0.5, 3.0}, {0.05, 0.2, 8.0}, {0.9, 0.77, 6.1}})
    check_max_shortcut(cloth, x);
}

}  // namespace
}  // namespace neurocloth::fuzzy
