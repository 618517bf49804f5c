#pragma once
// Evaluates a rule base: fuzzify the (clamped) inputs, fire every rule,
// accumulate the implied sets and defuzzify each output.
//
// Mamdani centroids are exact (to round-off) when every output set is piecewise
// linear (NOT keeps it so; very and somewhat on a consequent do not): the accumulated set is then
// linear between a finite list of points — the sets' corners, where a set crosses its activation
// level (ACT MIN), and where two implied sets cross (ACCU MAX) — and each piece is integrated in
// closed form. Other shapes are integrated by the trapezoid rule on
// kCentroidSamples intervals (error below 1e-6 of the range for the shapes the
// tests check against a 10x finer grid).
#include <Eigen/Core>

#include <string>
#include <vector>

#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth::fuzzy {

inline constexpr int kCentroidSamples = 20000;

struct InferenceReport {
  std::vector<double> outputs;                  // one per output variable
  std::vector<std::vector<double>> activation;  // [block][rule]: degree of fulfilment x weight
  std::vector<bool> clamped;                    // per input: was outside its range
  std::vector<bool> defaulted;                  // per output: no rule fired, default kept
  std::vector<std::string> notes;               // what was clamped or defaulted, in words
};

// Throws std::invalid_argument when inputs.size() differs from the system's.
InferenceReport infer(const FuzzySystem& system, const std::vector<double>& inputs);

// A tunable number of the rule base: a membership-function parameter of an
// input or output term (for Sugeno outputs, the consequent's constants), or a
// rule weight.
struct Parameter {
  enum class Kind { input_term, output_term, rule_weight };
  Kind kind;
  int variable;      // input/output index, or block index for rule weights
  int term;          // term index, or rule index for rule weights
  int index;         // parameter index within the term (0 for weights)
  std::string name;  // e.g. "mass.heavy[1]", "spring_constant.low[0]", "rules/RULE 3.weight"
};

std::vector<Parameter> parameters(const FuzzySystem& system);
double get_parameter(const FuzzySystem& system, const Parameter& p);
void set_parameter(FuzzySystem& system, const Parameter& p, double value);

struct InferenceGradient {
  InferenceReport report;
  std::vector<Parameter> parameters;
  Eigen::MatrixXd d_inputs;      // outputs x inputs
  Eigen::MatrixXd d_parameters;  // outputs x parameters
};

// Exact derivatives of every output (forward mode, same code as infer()) with
// respect to the inputs and every parameter (parameters(system)). Where a min,
// max or clamp picks one branch the derivative is that branch's; at a kink it
// is one-sided.
InferenceGradient infer_gradient(const FuzzySystem& system, const std::vector<double>& inputs);

// The same with respect to the inputs and `wrt` only (d_parameters has one
// column per entry of wrt, in its order; the numbers are those of the matching
// columns above). Cheaper when wrt is short: a derivative is carried only for
// what is asked, e.g. the tuned parameters, or none (wrt empty) for the inputs.
// Throws std::invalid_argument for a parameter the system does not have or
// one given twice.
InferenceGradient infer_gradient(const FuzzySystem& system, const std::vector<double>& inputs,
                                 const std::vector<Parameter>& wrt);

}  // namespace neurocloth::fuzzy
