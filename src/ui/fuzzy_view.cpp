#include "ui/fuzzy_view.h"

namespace neurocloth {

FuzzyView::FuzzyView(std::string rules_path, std::shared_ptr<const FuzzyMaterial> rules)
    : rules_path_(std::move(rules_path)), material_(std::move(rules)) {}

const DerivedMaterial& FuzzyView::evaluate(
    const std::vector<std::pair<std::string, double>>& inputs) {
  const fuzzy::FuzzySystem& system = material_->system();
  std::vector<double> x(system.inputs.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = 0.5 * (system.inputs[i].min + system.inputs[i].max);
  for (const auto& [name, value] : inputs)
    if (const int i = system.input_index(name); i >= 0) x[i] = value;
  if (x != evaluated_inputs_ || evaluated_.report.outputs.empty()) {
    std::map<std::string, double> named;
    for (std::size_t i = 0; i < x.size(); ++i)
      named[system.inputs[i].name] = x[i];
    evaluated_ = material_->derive(named);
    evaluated_inputs_ = x;
  }
  return evaluated_;
}

std::vector<float> FuzzyView::curve(const fuzzy::LinguisticVariable& variable, int term,
                                    int samples) {
  std::vector<float> mu(samples);
  const fuzzy::MembershipFunction& f = variable.terms[term].function;
  for (int s = 0; s < samples; ++s) {
    const double x = variable.min + (variable.max - variable.min) * s / (samples - 1);
    mu[s] = static_cast<float>(f(x));
  }
  return mu;
}

namespace {

std::string hedged(const std::vector<fuzzy::Hedge>& hedges, bool negated, const std::string& term) {
  std::string text = negated ? "NOT " : "";
  for (fuzzy::Hedge h : hedges)
    text += std::string(fuzzy::to_string(h)) + " ";
  return text + term;
}

}  // namespace

std::string FuzzyView::describe(const fuzzy::Condition& c) const {
  const fuzzy::FuzzySystem& system = material_->system();
  using Kind = fuzzy::Condition::Kind;
  if (c.kind == Kind::term) {
    const fuzzy::LinguisticVariable& v = system.inputs[c.variable];
    return v.name + " IS " + hedged(c.hedges, c.negated, v.terms[c.term].name);
  }
  if (c.kind == Kind::negation) return "NOT (" + describe(c.children.front()) + ")";
  std::string text;
  for (const fuzzy::Condition& child : c.children) {
    if (!text.empty()) text += c.kind == Kind::all ? " AND " : " OR ";
    const bool group = child.kind == Kind::all || child.kind == Kind::any;
    text += group ? "(" + describe(child) + ")" : describe(child);
  }
  return text;
}

std::string FuzzyView::describe(const fuzzy::Consequent& c) const {
  const fuzzy::LinguisticVariable& v = material_->system().outputs[c.variable];
  return v.name + " IS " + hedged(c.hedges, c.negated, v.terms[c.term].name);
}

}  // namespace neurocloth
