#pragma once
// Tuning a rule base to examples (docs/learning.md, "Tuning a rule base from
// examples"; ANFIS's hybrid learning, Jang 1993): given inputs and the outputs
// they should give, move the terms' parameters to minimise
//
//   E = 1/(N K) sum_n sum_k ((y_k(x_n) - t_nk) / range_k)^2
//
// over the N examples and the K named outputs (each error measured against its
// output's RANGE, so outputs of different scales weigh alike).
//  - Takagi-Sugeno consequents (COGS outputs): with the firing strengths fixed,
//    a weighted-average output is linear in its consequents' constants, so for
//    any membership functions they are solved exactly by least squares (the
//    smallest change from the rule base's values where the examples leave
//    them free).
//  - Membership functions of the inputs and Mamdani output sets: the gradient
//    of E (the engine's exact derivatives, infer_gradient), with the
//    consequents re-solved at every evaluation (so E is minimised over them,
//    and by the envelope theorem its gradient is the partial one), searched by
//    the spectral projected gradient under the readability constraints of
//    term_constraints.h.
// Only parameters that reach a named output through some rule are tuned.
#include <set>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/fuzzy/inference.h"
#include "learn/optim/optimizer.h"
#include "learn/rules/rule_examples.h"
#include "learn/rules/term_constraints.h"

namespace neurocloth {

struct RuleTuningOptions {
  bool input_terms = true;  // the inputs' membership functions (--what mf or inputs)
  bool output_sets = true;  // Mamdani output sets (--what mf or sets)
  bool consequents = true;  // Takagi-Sugeno consequents (--what consequents)
  double min_width = 0.02;  // a tuned set's narrowest span, as a fraction of its range
  // The search's budgets and tolerances (method and lbfgs_memory are ignored).
  OptimizerOptions search = default_search();

  static OptimizerOptions default_search();
};

class RuleTuning {
 public:
  // Throws InputError naming the examples' file when nothing can be tuned for
  // the named outputs, or when there are fewer examples than the tuned
  // parameters need (examples_needed()).
  RuleTuning(const fuzzy::FuzzySystem& system, const RuleExamples& examples,
             const RuleTuningOptions& options);

  // Tuned by the gradient search (as theta, each divided by its variable's range).
  const std::vector<fuzzy::Parameter>& shape_parameters() const { return shapes_; }
  // Solved by least squares.
  const std::vector<fuzzy::Parameter>& consequent_parameters() const { return consequents_; }
  // At least one residual per tuned parameter, and for each Sugeno output one
  // example per consequent constant.
  std::size_t examples_needed() const { return needed_; }

  Eigen::VectorXd initial() const;
  // The rule base with `theta` and the consequents solved for it.
  fuzzy::FuzzySystem system_at(const Eigen::VectorXd& theta) const;
  double loss(const Eigen::VectorXd& theta, Eigen::VectorXd* gradient) const;
  // theta moved inside the constraints; `active` as TermConstraints::project.
  Eigen::VectorXd project(const Eigen::VectorXd& theta,
                          std::set<std::string>* active = nullptr) const;

  // [example][k]: what `s` gives for the named outputs.
  std::vector<std::vector<double>> outputs_of(const fuzzy::FuzzySystem& s) const;
  double loss_of(const std::vector<std::vector<double>>& outputs) const;
  const RuleExamples& examples() const { return examples_; }
  const fuzzy::FuzzySystem& start() const { return start_; }

 private:
  fuzzy::FuzzySystem with_shapes(const Eigen::VectorXd& theta) const;
  void solve_consequents(fuzzy::FuzzySystem& s) const;

  fuzzy::FuzzySystem start_;
  const RuleExamples& examples_;
  std::vector<fuzzy::Parameter> shapes_, consequents_;
  std::vector<double> shape_scale_;   // each shape parameter's variable range
  std::vector<double> output_range_;  // per named output
  TermConstraints constraints_;
  std::size_t needed_ = 0;
};

struct RuleTuningResult {
  fuzzy::FuzzySystem tuned;
  bool searched = false;   // false: only least squares ran (no shapes tuned)
  OptimizerResult search;  // the gradient search, when it ran
  std::vector<std::vector<double>> before, after;  // [example][k] outputs
  double loss_before = 0, loss_after = 0;
  std::vector<std::string> active;  // constraints holding terms at the end, in words
};

// Runs the tuning; `callback` sees every iteration of the search.
RuleTuningResult tune_rules(const RuleTuning& problem, const RuleTuningOptions& options,
                            const IterationCallback& callback = {});

// Per named output: the root mean square of output - target, in its unit.
std::vector<double> rmse_per_output(const RuleExamples& examples,
                                    const std::vector<std::vector<double>>& outputs);
// Per example: the root mean square over the named outputs of (output - target) / range.
std::vector<double> rmse_per_example(const fuzzy::FuzzySystem& system, const RuleExamples& examples,
                                     const std::vector<std::vector<double>>& outputs);

// The terms whose parameters differ, one line each:
// "mass.medium: trian 0.08 0.3 0.6 -> trian 0.08 0.35 0.6".
std::vector<std::string> changed_terms(const fuzzy::FuzzySystem& before,
                                       const fuzzy::FuzzySystem& after);

}  // namespace neurocloth
