// Tuning a rule base to examples (src/learn/rule_tuning.h): planted changes
// recovered from examples the changed rule base gives, the readability
// constraints held when the examples pull against them, and the loss's
// gradient against central differences.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "core/fuzzy/formats/fcl_reader.h"
#include "core/fuzzy/inference.h"
#include "core/io/input_error.h"
#include "learn/rules/rule_tuning.h"
#include "learn/rules/term_constraints.h"

namespace neurocloth {
namespace {

using fuzzy::FuzzySystem;

// One input, three triangles; a Sugeno output (singletons and a linear
// consequent) and a Mamdani output with three triangle sets.
const char* kTuningRules = R"(
FUNCTION_BLOCK small
VAR_INPUT x : REAL; z : REAL; END_VAR
VAR_OUTPUT y : REAL; s : REAL; END_VAR
FUZZIFY x
  RANGE := (0 .. 10);
  TERM low := trian 0 0 5;
  TERM mid := trian 0 5 10;
  TERM high := trian 5 10 10;
END_FUZZIFY
FUZZIFY z
  RANGE := (0 .. 1);
  TERM any := trape 0 0 1 1;
END_FUZZIFY
DEFUZZIFY y
  RANGE := (0 .. 100);
  TERM a := 10;
  TERM b := 40;
  TERM c := linear 50 x 3 z 0;
  METHOD : COGS;
  DEFAULT := 0;
END_DEFUZZIFY
DEFUZZIFY s
  RANGE := (0 .. 10);
  TERM lo := trian 0 2 4;
  TERM md := trian 3 5 7;
  TERM hi := trian 6 8 10;
  METHOD : COG;
  DEFAULT := 5;
END_DEFUZZIFY
RULEBLOCK r
  AND : MIN; OR : MAX; ACT : MIN; ACCU : MAX;
  RULE 1 : IF x IS low THEN y IS a, s IS lo;
  RULE 2 : IF x IS mid THEN y IS b, s IS md;
  RULE 3 : IF x IS high AND z IS any THEN y IS c, s IS hi;
END_RULEBLOCK
END_FUNCTION_BLOCK
)";

FuzzySystem small() {
  return fuzzy::parse_fcl(kTuningRules, "small.fcl");
}

fuzzy::Parameter parameter(const FuzzySystem& s, const std::string& name) {
  for (const auto& p : fuzzy::parameters(s))
    if (p.name == name) return p;
  ADD_FAILURE() << "test bug: no parameter " << name;
  return {};
}

void set(FuzzySystem& s, const std::string& name, double v) {
  fuzzy::set_parameter(s, parameter(s, name), v);
}
double get(const FuzzySystem& s, const std::string& name) {
  return fuzzy::get_parameter(s, parameter(s, name));
}

// `count` examples of what `truth` gives for `outputs`, inputs spread evenly
// over x (and a fixed pseudo-random z).
RuleExamples examples_of(const FuzzySystem& truth, const std::vector<std::string>& outputs,
                         int count) {
  RuleExamples e;
  e.path = "examples.csv";
  for (const auto& o : outputs)
    e.outputs.push_back(truth.output_index(o));
  std::mt19937 random(7);
  for (int n = 0; n < count; ++n) {
    const double x = 10.0 * (n + 0.5) / count, z = double(random() % 1000) / 1000.0;
    const auto r = fuzzy::infer(truth, {x, z});
    e.inputs.push_back({x, z});
    e.targets.emplace_back();
    for (int o : e.outputs)
      e.targets.back().push_back(r.outputs[o]);
    e.lines.push_back(n + 2);
  }
  return e;
}

RuleTuningOptions options(bool mf, bool consequents) {
  RuleTuningOptions o;
  o.input_terms = o.output_sets = mf;
  o.consequents = consequents;
  return o;
}

TEST(RuleTuning, LeastSquaresRecoversChangedConsequentsExactly) {
  FuzzySystem truth = small();
  set(truth, "y.b[0]", 47.5);
  set(truth, "y.c[0]", 20);
  set(truth, "y.c[1]", 6.25);
  const RuleExamples e = examples_of(truth, {"y"}, 30);
  const RuleTuning problem(small(), e, options(false, true));
  EXPECT_TRUE(problem.shape_parameters().empty());
  const RuleTuningResult r = tune_rules(problem, options(false, true));
  EXPECT_FALSE(r.searched);
  // Each bound is a small margin over what was measured (the same bits in
  // every build). Measured: every value within 5.6e-15, the loss 2.9e-33.
  const double exact = 5e-14;
  EXPECT_NEAR(get(r.tuned, "y.b[0]"), 47.5, exact);
  EXPECT_NEAR(get(r.tuned, "y.c[0]"), 20, exact);
  EXPECT_NEAR(get(r.tuned, "y.c[1]"), 6.25, exact);
  EXPECT_NEAR(get(r.tuned, "y.a[0]"), 10, exact);  // unchanged, and not moved
  // z's coefficient is free only in combination with the others: z varies, so it is seen.
  EXPECT_NEAR(get(r.tuned, "y.c[2]"), 0, exact);
  EXPECT_GT(r.loss_before, 1e-4);
  EXPECT_LT(r.loss_after, 3e-32);
}

TEST(RuleTuning, RecoversAShiftedInputTerm) {
  FuzzySystem truth = small();
  set(truth, "x.mid[1]", 6.5);
  const RuleExamples e = examples_of(truth, {"y"}, 40);
  const RuleTuningOptions o = options(true, false);
  const RuleTuning problem(small(), e, o);
  const RuleTuningResult r = tune_rules(problem, o);
  EXPECT_TRUE(r.searched);
  // Measured: the peak within 1.7e-10, the loss down to 6.2e-19 of its start.
  EXPECT_NEAR(get(r.tuned, "x.mid[1]"), 6.5, 1e-9) << r.search.message;
  EXPECT_LT(r.loss_after, 5e-18 * r.loss_before) << r.search.message;
}

TEST(RuleTuning, RecoversAMovedMamdaniSet) {
  FuzzySystem truth = small();
  set(truth, "s.md[1]", 5.8);
  set(truth, "s.md[2]", 7.4);
  const RuleExamples e = examples_of(truth, {"s"}, 40);
  // The sets only (--what sets): with the input terms free too, some
  // combinations of both barely change the centroid. Even alone, a set clipped
  // by its rule (ACT MIN) shows the centroid only through its visible part, so
  // the search stalls with the loss 1e-5 of its start and the corners most of
  // the way back, not exactly. Measured: the loss down to 1.40e-5 of its
  // start, the corners 0.073 and 0.081 short.
  RuleTuningOptions o = options(false, false);
  o.output_sets = true;
  const RuleTuning problem(small(), e, o);
  const RuleTuningResult r = tune_rules(problem, o);
  EXPECT_LT(r.loss_after, 1.5e-5 * r.loss_before) << r.search.message;
  EXPECT_NEAR(get(r.tuned, "s.md[1]"), 5.8, 0.08);
  EXPECT_NEAR(get(r.tuned, "s.md[2]"), 7.4, 0.09);
  EXPECT_TRUE(changed_terms(small(), r.tuned).size() >= 1);
}

TEST(RuleTuning, HybridTunesTermsAndConsequentsTogether) {
  FuzzySystem truth = small();
  set(truth, "x.mid[1]", 4.0);
  set(truth, "y.b[0]", 55);
  const RuleExamples e = examples_of(truth, {"y"}, 40);
  const RuleTuningOptions o = options(true, true);
  const RuleTuning problem(small(), e, o);
  EXPECT_FALSE(problem.consequent_parameters().empty());
  const RuleTuningResult r = tune_rules(problem, o);
  // Measured (the 500 iterations' budget spent): the loss down to 2.8e-10
  // of its start, the consequent 0.0035 and the peak 4.8e-4 short.
  EXPECT_LT(r.loss_after, 3e-10 * r.loss_before) << r.search.message;
  EXPECT_NEAR(get(r.tuned, "y.b[0]"), 55, 0.004);
  EXPECT_NEAR(get(r.tuned, "x.mid[1]"), 4.0, 6e-4);
}

// Every tuned term valid and readable: corners in order, inside the range
// (or where it started), at least the minimum width, centres in order.
void expect_readable(const FuzzySystem& s, const FuzzySystem& start, double min_width) {
  for (const auto* vars : {&s.inputs, &s.outputs})
    for (std::size_t v = 0; v < vars->size(); ++v) {
      const auto& var = (*vars)[v];
      const auto& var0 = (vars == &s.inputs ? start.inputs : start.outputs)[v];
      double last_centre = -INFINITY;
      for (std::size_t t = 0; t < var.terms.size(); ++t) {
        const auto& f = var.terms[t].function;
        const std::string name = var.name + "." + var.terms[t].name;
        EXPECT_EQ(f.validate(), "") << name;
        if (f.shape != fuzzy::Shape::triangle && f.shape != fuzzy::Shape::trapezoid) continue;
        for (std::size_t k = 0; k < f.params.size(); ++k) {
          EXPECT_GE(f.params[k], std::min(var.min, var0.terms[t].function.params[k])) << name;
          EXPECT_LE(f.params[k], std::max(var.max, var0.terms[t].function.params[k])) << name;
        }
        EXPECT_GE(f.params.back() - f.params.front(), min_width * (var.max - var.min) * (1 - 1e-9))
            << name;
        const double c = term_centre(f);
        EXPECT_GE(c, last_centre) << name;
        last_centre = c;
      }
    }
}

TEST(RuleTuning, TermsStayReadableWhenTheExamplesPullThemApart) {
  // Targets no rule base of this shape can give: s at its top everywhere,
  // which pulls every set to the right end and the sets past each other.
  RuleExamples e = examples_of(small(), {"s"}, 30);
  for (auto& t : e.targets)
    t[0] = 10;
  RuleTuningOptions o = options(true, false);
  o.search.max_iterations = 200;
  const FuzzySystem start = small();
  const RuleTuning problem(start, e, o);
  const RuleTuningResult r = tune_rules(problem, o);
  EXPECT_LT(r.loss_after, 2.2e-4 * r.loss_before);  // measured 1.92e-4 (0.278 -> 5.3e-5)
  expect_readable(r.tuned, start, o.min_width);
  ASSERT_FALSE(r.active.empty());
  bool at_end = false;
  for (const auto& a : r.active)
    at_end = at_end || a.find("held at the range's end 10") != std::string::npos;
  EXPECT_TRUE(at_end) << r.active.front();
}

TEST(RuleTuning, ProjectionKeepsOrderWidthAndRange) {
  const FuzzySystem start = small();
  RuleExamples e = examples_of(start, {"y", "s"}, 20);
  const RuleTuning problem(start, e, options(true, false));
  // Scramble every tuned parameter far outside, then project.
  Eigen::VectorXd theta = problem.initial();
  std::mt19937 random(3);
  for (Eigen::Index j = 0; j < theta.size(); ++j)
    theta[j] = double(random() % 4000) / 1000.0 - 1.5;
  std::set<std::string> active;
  const Eigen::VectorXd p = problem.project(theta, &active);
  EXPECT_FALSE(active.empty());
  expect_readable(problem.system_at(p), start, 0.02);
  // A point inside stays where it is.
  EXPECT_EQ(problem.project(problem.initial()), problem.initial());
}

TEST(RuleTuning, LossGradientMatchesCentralDifferences) {
  FuzzySystem truth = small();
  set(truth, "x.mid[1]", 6.1);
  set(truth, "s.hi[1]", 8.6);
  const RuleExamples e = examples_of(truth, {"y", "s"}, 17);
  const RuleTuning problem(small(), e, options(true, true));
  // Away from the kinks: every corner nudged off the examples' grid.
  Eigen::VectorXd theta = problem.initial();
  for (Eigen::Index j = 0; j < theta.size(); ++j)
    theta[j] += 0.0013 * double(j % 5 + 1);
  theta = problem.project(theta);
  Eigen::VectorXd g;
  problem.loss(theta, &g);
  ASSERT_EQ(g.size(), theta.size());
  double largest = 0;
  for (Eigen::Index j = 0; j < g.size(); ++j)
    largest = std::max(largest, std::abs(g[j]));
  ASSERT_GT(largest, 0);
  for (Eigen::Index j = 0; j < theta.size(); ++j) {
    const double h = 1e-6;
    Eigen::VectorXd up = theta, down = theta;
    up[j] += h;
    down[j] -= h;
    const double fd = (problem.loss(up, nullptr) - problem.loss(down, nullptr)) / (2 * h);
    EXPECT_NEAR(g[j], fd, 1e-5 * largest + 1e-6 * std::abs(fd))
        << problem.shape_parameters()[std::size_t(j)].name;
  }
}

TEST(RuleTuning, TooFewExamplesSayHowManyAreNeeded) {
  const RuleExamples e = examples_of(small(), {"y"}, 3);
  try {
    RuleTuning problem(small(), e, options(true, true));
    FAIL() << "3 examples accepted";
  } catch (const InputError& err) {
    const std::string what = err.what();
    EXPECT_NE(what.find("examples.csv"), std::string::npos) << what;
    EXPECT_NE(what.find("at least"), std::string::npos) << what;
    EXPECT_NE(what.find("3 example"), std::string::npos) << what;
  }
}

TEST(RuleTuning, NothingToTuneIsRefused) {
  // s is a Mamdani output: consequents only has nothing to move.
  const RuleExamples e = examples_of(small(), {"s"}, 20);
  EXPECT_THROW(RuleTuning(small(), e, options(false, true)), InputError);
}

TEST(RuleTuning, ReportsWhatMoved) {
  FuzzySystem moved = small();
  set(moved, "x.mid[1]", 5.5);
  const auto lines = changed_terms(small(), moved);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "x.mid: trian 0 5 10 -> trian 0 5.5 10");
}

}  // namespace
}  // namespace neurocloth
