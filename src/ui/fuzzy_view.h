#pragma once
// The fuzzy material as the Material panel shows it, computed on the UI side
// from the rule base and the UI's current inputs (the simulation thread does
// its own inference when an input reaches it): each variable's membership
// curves, each rule's firing strength and the resulting parameters.
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/scene/fuzzy_material.h"

namespace neurocloth {

class FuzzyView {
 public:
  // `rules` was read from `rules_path` (a scene's, or one the user loads).
  FuzzyView(std::string rules_path, std::shared_ptr<const FuzzyMaterial> rules);

  const std::string& rules_path() const { return rules_path_; }
  const std::shared_ptr<const FuzzyMaterial>& rules() const { return material_; }
  const fuzzy::FuzzySystem& system() const { return material_->system(); }

  // The material and the rules' activations for `inputs` (name, value). Inputs
  // the rule base has but the list lacks take the middle of their range, so a
  // list that lags a rule-base change still shows something; extras are ignored.
  const DerivedMaterial& evaluate(const std::vector<std::pair<std::string, double>>& inputs);

  // mu of `term` of `variable` at `samples` points evenly spread over its range.
  static std::vector<float> curve(const fuzzy::LinguisticVariable& variable, int term, int samples);
  // "mass IS small AND force IS NOT big": a rule's condition as FCL would write it.
  std::string describe(const fuzzy::Condition& condition) const;
  std::string describe(const fuzzy::Consequent& consequent) const;

 private:
  std::string rules_path_;
  std::shared_ptr<const FuzzyMaterial> material_;
  // The last evaluation, reused while the inputs stay the same (every frame, mostly).
  std::vector<double> evaluated_inputs_;
  DerivedMaterial evaluated_;
};

}  // namespace neurocloth
