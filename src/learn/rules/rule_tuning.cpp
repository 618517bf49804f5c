#include "learn/rules/rule_tuning.h"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/io/input_error.h"

namespace neurocloth {
namespace {

using fuzzy::Condition;
using fuzzy::Defuzzification;
using fuzzy::FuzzySystem;
using fuzzy::Parameter;

bool named(const RuleExamples& e, int output) {
  return std::find(e.outputs.begin(), e.outputs.end(), output) != e.outputs.end();
}

void leaves(const Condition& c, std::vector<std::pair<int, int>>& out) {
  if (c.kind == Condition::Kind::term) out.emplace_back(c.variable, c.term);
  for (const Condition& child : c.children)
    leaves(child, out);
}

// The terms that reach a named output through a rule, by what tunes them:
// input terms and Mamdani sets (gradient), Sugeno consequents (least squares).
struct Reach {
  std::vector<TermRef> shapes;                  // inputs first, then Mamdani output sets
  std::vector<std::pair<int, int>> consequent;  // (output, term)
};

Reach reach(const FuzzySystem& s, const RuleExamples& e, const RuleTuningOptions& o) {
  std::set<std::pair<int, int>> inputs, sets, consequent;
  for (const auto& block : s.blocks)
    for (const auto& rule : block.rules) {
      bool reaches = false;
      for (const auto& c : rule.consequents) {
        if (!named(e, c.variable)) continue;
        reaches = true;
        if (s.outputs[c.variable].method == Defuzzification::centroid)
          sets.insert({c.variable, c.term});
        else
          consequent.insert({c.variable, c.term});
      }
      if (!reaches) continue;
      std::vector<std::pair<int, int>> terms;
      leaves(rule.condition, terms);
      inputs.insert(terms.begin(), terms.end());
    }
  Reach r;
  if (o.input_terms)
    for (const auto& [v, t] : inputs)
      if (!tunable_indices(s.inputs[v].terms[t].function).empty()) r.shapes.push_back({true, v, t});
  if (o.output_sets)
    for (const auto& [v, t] : sets)
      if (!tunable_indices(s.outputs[v].terms[t].function).empty())
        r.shapes.push_back({false, v, t});
  if (o.consequents) r.consequent.assign(consequent.begin(), consequent.end());
  return r;
}

std::string names_of(const FuzzySystem& s, const RuleExamples& e) {
  std::string out;
  for (int o : e.outputs)
    out += (out.empty() ? "" : ", ") + s.outputs[o].name;
  return out;
}

std::string shape_text(const fuzzy::MembershipFunction& f) {
  std::string out = fuzzy::to_string(f.shape);
  char buf[32];
  for (double p : f.params) {
    std::snprintf(buf, sizeof buf, " %.6g", p);
    out += buf;
  }
  return out;
}

// The --what that `o` stands for, for messages.
std::string what(const RuleTuningOptions& o) {
  std::string out;
  auto add = [&](bool on, const char* name) {
    if (on) out += (out.empty() ? "" : ",") + std::string(name);
  };
  add(o.input_terms && o.output_sets, "mf");
  add(o.input_terms && !o.output_sets, "inputs");
  add(!o.input_terms && o.output_sets, "sets");
  add(o.consequents, "consequents");
  return out;
}

}  // namespace

OptimizerOptions RuleTuningOptions::default_search() {
  OptimizerOptions o;
  o.max_iterations = 500;
  o.loss_tolerance = 1e-24;  // an RMS error of 1e-12 of the ranges: exact, to rounding
  o.gradient_tolerance = 1e-9;
  o.stall_iterations = 20;
  o.stall_tolerance = 1e-9;
  return o;
}

RuleTuning::RuleTuning(const FuzzySystem& system, const RuleExamples& examples,
                       const RuleTuningOptions& options)
    : start_(system),
      examples_(examples),
      constraints_(system, reach(system, examples, options).shapes, options.min_width) {
  const Reach r = reach(system, examples, options);
  const std::vector<Parameter> all = fuzzy::parameters(system);
  for (std::size_t c = 0; c < all.size(); ++c) {
    const Parameter& p = all[c];
    if (p.kind == Parameter::Kind::rule_weight) continue;
    const bool input = p.kind == Parameter::Kind::input_term;
    const auto& var = input ? system.inputs[p.variable] : system.outputs[p.variable];
    const bool shape = std::any_of(r.shapes.begin(), r.shapes.end(), [&](const TermRef& t) {
      return t.input == input && t.variable == p.variable && t.term == p.term;
    });
    const auto idx = tunable_indices(var.terms[p.term].function);
    if (shape && std::find(idx.begin(), idx.end(), p.index) != idx.end()) {
      shapes_.push_back(p);
      shape_scale_.push_back(var.max - var.min);
    }
    if (!input && std::find(r.consequent.begin(), r.consequent.end(),
                            std::pair<int, int>{p.variable, p.term}) != r.consequent.end()) {
      consequents_.push_back(p);
    }
  }
  for (int o : examples.outputs)
    output_range_.push_back(system.outputs[o].max - system.outputs[o].min);

  const std::string outputs = names_of(system, examples);
  if (shapes_.empty() && consequents_.empty())
    throw InputError(examples.path, "header",
                     "nothing to tune for " + outputs + " with --what " + what(options) +
                         ": no rule reaches them through a term that setting tunes");
  // One residual per tuned number at least; a Sugeno output's least squares
  // needs one example per constant of its own.
  const std::size_t k = examples.outputs.size(), total = shapes_.size() + consequents_.size();
  needed_ = (total + k - 1) / k;
  for (int o : examples.outputs) {
    std::size_t own = 0;
    for (const Parameter& p : consequents_)
      own += p.variable == o;
    needed_ = std::max(needed_, own);
  }
  if (examples.size() < needed_)
    throw InputError(examples.path, "examples",
                     std::to_string(examples.size()) + " example(s) for " + std::to_string(total) +
                         " tuned parameters (" + std::to_string(shapes_.size()) +
                         " of membership functions and sets, " +
                         std::to_string(consequents_.size()) + " consequent constants) over " +
                         outputs + ": at least " + std::to_string(needed_) + " are needed");
}

Eigen::VectorXd RuleTuning::initial() const {
  Eigen::VectorXd theta(Eigen::Index(shapes_.size()));
  for (std::size_t j = 0; j < shapes_.size(); ++j)
    theta[Eigen::Index(j)] = fuzzy::get_parameter(start_, shapes_[j]) / shape_scale_[j];
  return theta;
}

FuzzySystem RuleTuning::with_shapes(const Eigen::VectorXd& theta) const {
  FuzzySystem s = start_;
  for (std::size_t j = 0; j < shapes_.size(); ++j)
    fuzzy::set_parameter(s, shapes_[j], theta[Eigen::Index(j)] * shape_scale_[j]);
  return s;
}

void RuleTuning::solve_consequents(FuzzySystem& s) const {
  if (consequents_.empty()) return;
  const Eigen::Index n = Eigen::Index(examples_.size());
  // Per named output: the design matrix (d output / d constant: the
  // normalised firing strengths, times the inputs for linear consequents) and
  // what is left to explain. The output is linear in the constants, so one
  // exact derivative per example gives the whole problem.
  std::vector<Eigen::MatrixXd> a(examples_.outputs.size());
  std::vector<Eigen::VectorXd> b(examples_.outputs.size());
  std::vector<std::vector<std::size_t>> cols(examples_.outputs.size());
  for (std::size_t k = 0; k < examples_.outputs.size(); ++k) {
    for (std::size_t j = 0; j < consequents_.size(); ++j)
      if (consequents_[j].variable == examples_.outputs[k]) cols[k].push_back(j);
    a[k].setZero(n, Eigen::Index(cols[k].size()));
    b[k].setZero(n);
  }
  for (Eigen::Index e = 0; e < n; ++e) {
    const fuzzy::InferenceGradient g = fuzzy::infer_gradient(s, examples_.inputs[e], consequents_);
    for (std::size_t k = 0; k < examples_.outputs.size(); ++k) {
      const int o = examples_.outputs[k];
      b[k][e] = examples_.targets[e][k] - g.report.outputs[o];
      for (std::size_t c = 0; c < cols[k].size(); ++c)
        a[k](e, Eigen::Index(c)) = g.d_parameters(o, Eigen::Index(cols[k][c]));
    }
  }
  for (std::size_t k = 0; k < examples_.outputs.size(); ++k) {
    if (cols[k].empty()) continue;
    // The least-squares change of smallest norm: constants no example
    // reaches (a rule that never fires) keep their values.
    const Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(a[k]);
    const Eigen::VectorXd delta = cod.solve(b[k]);
    for (std::size_t c = 0; c < cols[k].size(); ++c) {
      const Parameter& p = consequents_[cols[k][c]];
      fuzzy::set_parameter(s, p, fuzzy::get_parameter(s, p) + delta[Eigen::Index(c)]);
    }
  }
}

FuzzySystem RuleTuning::system_at(const Eigen::VectorXd& theta) const {
  FuzzySystem s = with_shapes(theta);
  solve_consequents(s);
  return s;
}

double RuleTuning::loss(const Eigen::VectorXd& theta, Eigen::VectorXd* gradient) const {
  const FuzzySystem s = system_at(theta);
  const std::size_t k_count = examples_.outputs.size();
  const double scale = 1.0 / double(examples_.size() * k_count);
  if (gradient) gradient->setZero(Eigen::Index(shapes_.size()));
  double sum = 0;
  for (std::size_t e = 0; e < examples_.size(); ++e) {
    const bool derive = gradient && !shapes_.empty();
    fuzzy::InferenceGradient g;
    if (derive)
      g = fuzzy::infer_gradient(s, examples_.inputs[e], shapes_);
    else
      g.report = fuzzy::infer(s, examples_.inputs[e]);
    for (std::size_t k = 0; k < k_count; ++k) {
      const int o = examples_.outputs[k];
      const double r = (g.report.outputs[o] - examples_.targets[e][k]) / output_range_[k];
      sum += r * r;
      if (!derive) continue;
      for (std::size_t j = 0; j < shapes_.size(); ++j)
        (*gradient)[Eigen::Index(j)] +=
            2 * r / output_range_[k] * g.d_parameters(o, Eigen::Index(j)) * shape_scale_[j];
    }
  }
  if (gradient) *gradient *= scale;
  return sum * scale;
}

Eigen::VectorXd RuleTuning::project(const Eigen::VectorXd& theta,
                                    std::set<std::string>* active) const {
  FuzzySystem s = with_shapes(theta);
  constraints_.project(s, active);
  Eigen::VectorXd out(theta.size());
  for (std::size_t j = 0; j < shapes_.size(); ++j)
    out[Eigen::Index(j)] = fuzzy::get_parameter(s, shapes_[j]) / shape_scale_[j];
  return out;
}

std::vector<std::vector<double>> RuleTuning::outputs_of(const FuzzySystem& s) const {
  std::vector<std::vector<double>> out;
  for (const auto& x : examples_.inputs) {
    const fuzzy::InferenceReport r = fuzzy::infer(s, x);
    out.emplace_back();
    for (int o : examples_.outputs)
      out.back().push_back(r.outputs[o]);
  }
  return out;
}

double RuleTuning::loss_of(const std::vector<std::vector<double>>& outputs) const {
  double sum = 0;
  for (std::size_t e = 0; e < outputs.size(); ++e)
    for (std::size_t k = 0; k < output_range_.size(); ++k) {
      const double r = (outputs[e][k] - examples_.targets[e][k]) / output_range_[k];
      sum += r * r;
    }
  return sum / double(outputs.size() * output_range_.size());
}

RuleTuningResult tune_rules(const RuleTuning& problem, const RuleTuningOptions& options,
                            const IterationCallback& callback) {
  RuleTuningResult r;
  r.before = problem.outputs_of(problem.start());
  r.loss_before = problem.loss_of(r.before);
  Eigen::VectorXd best = problem.initial();
  if (!problem.shape_parameters().empty()) {
    r.searched = true;
    const Objective objective = [&](const Eigen::VectorXd& theta, Eigen::VectorXd* gradient) {
      return problem.loss(theta, gradient);
    };
    const Projection projection = [&](const Eigen::VectorXd& theta) {
      return problem.project(theta);
    };
    r.search = minimize_projected(objective, projection, best, options.search, callback);
    if (r.search.best_theta.size() == best.size()) best = problem.project(r.search.best_theta);
    // Which constraints hold the result: those a short step down the gradient
    // would break (a constraint that is merely met, with the loss pulling the
    // term inwards, is not holding anything).
    Eigen::VectorXd g;
    problem.loss(best, &g);
    const double biggest = g.cwiseAbs().maxCoeff();
    if (biggest > 0 && std::isfinite(biggest)) {
      std::set<std::string> active;
      problem.project(best - (1e-6 / biggest) * g, &active);
      r.active.assign(active.begin(), active.end());
    }
  }
  r.tuned = problem.system_at(best);
  r.after = problem.outputs_of(r.tuned);
  r.loss_after = problem.loss_of(r.after);
  return r;
}

std::vector<double> rmse_per_output(const RuleExamples& e,
                                    const std::vector<std::vector<double>>& outputs) {
  std::vector<double> out(e.outputs.size(), 0.0);
  for (std::size_t n = 0; n < outputs.size(); ++n)
    for (std::size_t k = 0; k < out.size(); ++k) {
      const double d = outputs[n][k] - e.targets[n][k];
      out[k] += d * d;
    }
  for (double& v : out)
    v = std::sqrt(v / double(outputs.size()));
  return out;
}

std::vector<double> rmse_per_example(const FuzzySystem& s, const RuleExamples& e,
                                     const std::vector<std::vector<double>>& outputs) {
  std::vector<double> out;
  for (std::size_t n = 0; n < outputs.size(); ++n) {
    double sum = 0;
    for (std::size_t k = 0; k < e.outputs.size(); ++k) {
      const auto& v = s.outputs[e.outputs[k]];
      const double d = (outputs[n][k] - e.targets[n][k]) / (v.max - v.min);
      sum += d * d;
    }
    out.push_back(std::sqrt(sum / double(e.outputs.size())));
  }
  return out;
}

std::vector<std::string> changed_terms(const FuzzySystem& before, const FuzzySystem& after) {
  std::vector<std::string> out;
  auto compare = [&](const std::vector<fuzzy::LinguisticVariable>& a,
                     const std::vector<fuzzy::LinguisticVariable>& b) {
    for (std::size_t v = 0; v < a.size(); ++v)
      for (std::size_t t = 0; t < a[v].terms.size(); ++t) {
        const auto& fa = a[v].terms[t].function;
        const auto& fb = b[v].terms[t].function;
        if (fa.params == fb.params) continue;
        out.push_back(a[v].name + "." + a[v].terms[t].name + ": " + shape_text(fa) + " -> " +
                      shape_text(fb));
      }
  };
  compare(before.inputs, after.inputs);
  compare(before.outputs, after.outputs);
  return out;
}

}  // namespace neurocloth
