// What a fit hands back (fit_problem.h): theta written into a copy of the
// scene, its material and modules (fitted_scene), the fitted inputs in the
// rule base's words, and the network's every weight for the side file when
// the scene alone does not rebuild them (fitted_output.h).
#include <cmath>
#include <string>
#include <vector>

#include "core/fuzzy/term_degrees.h"
#include "learn/fit/fit_problem_impl.h"

namespace neurocloth {
using namespace fit_detail;

Scene FitProblem::fitted_scene(const Eigen::VectorXd& theta_in) const {
  const Eigen::VectorXd theta = impl_->inside(theta_in);
  Scene s = impl_->scene;
  for (const Unknown& u : impl_->unknowns) {
    if (u.per_element) continue;
    const double t = theta[static_cast<Eigen::Index>(u.block.offset)];
    const double v = u.block.log_space ? std::exp(t) : t;
    // A family that followed the spring constant (< 0) was fitted with it and
    // follows it still; one with its own value keeps it unless fitted itself.
    if (u.block.name == "spring_constant") {
      s.material.spring_constant = v;
    } else if (u.block.name == "shear_constant") {
      s.material.shear_constant = v;
    } else if (u.block.name == "bend_constant") {
      s.material.bend_constant = v;
    } else if (u.target == Target::viscosity) {
      s.material.viscosity = v;
    } else if (u.target == Target::node_mass) {
      s.material.node_mass = v;
    } else if (u.target == Target::friction) {
      s.material.friction = v;
    } else if (u.target == Target::rest_length) {
      continue;  // a scene derives lengths from positions: they go to the side file
    } else if (u.target == Target::path) {
      set_path(s.modules[std::size_t(u.declaration)].spec, u, theta);
    } else if (u.target == Target::initial_velocity) {
      const auto o = static_cast<Eigen::Index>(u.block.offset);
      s.initial_velocity = Vec3(theta[o], theta[o + 1], theta[o + 2]);
    } else if (u.declaration >= 0) {
      set_spec_parameter(s.modules[static_cast<std::size_t>(u.declaration)].spec, u.id, v);
    }
  }
  if (impl_->words) {  // the material stays in words, at the fitted inputs
    const DerivedMaterial d = s.fuzzy_material->rules->derive(impl_->inputs_at(theta));
    s.fuzzy_material->inputs = impl_->inputs_at(theta);
    s.fuzzy_material->notes = d.report.notes;
    s.material = d.material;
  } else {
    s.fuzzy_material.reset();
  }
  return s;
}

std::vector<std::string> FitProblem::inputs_in_words(const Eigen::VectorXd& theta_in) const {
  const Eigen::VectorXd theta = impl_->inside(theta_in);
  std::vector<std::string> words;
  for (const Unknown& u : impl_->unknowns)
    if (u.target == Target::input)
      words.push_back(fuzzy::in_words(
          impl_->scene.fuzzy_material->rules->system().inputs[static_cast<std::size_t>(u.input)],
          theta[static_cast<Eigen::Index>(u.block.offset)]));
  return words;
}

const fuzzy::LinguisticVariable* FitProblem::input_variable(const FitBlock& block) const {
  for (const Unknown& u : impl_->unknowns)
    if (u.target == Target::input && u.block.offset == block.offset)
      return &impl_->scene.fuzzy_material->rules->system()
                  .inputs[static_cast<std::size_t>(u.input)];
  return nullptr;
}

MaterialWeights FitProblem::element_weights(const Eigen::VectorXd& theta) const {
  // Every weight, also for a family fit: the side file is written only when
  // they differ from what FITTED.json's material builds (fitted_output.h), as
  // they do for numbers fitted to a material in words (each node's mass
  // share came from the rule base).
  impl_->apply(impl_->inside(theta));
  const ClothNetwork& net = impl_->model.net;
  return {net.springs.stiffness, net.springs.damping, net.masses.inverse_mass, net.masses.friction};
}

std::vector<double> FitProblem::element_rest_lengths(const Eigen::VectorXd& theta) const {
  for (const Unknown& u : impl_->unknowns)
    if (u.target == Target::rest_length) {
      impl_->apply(impl_->inside(theta));
      return impl_->model.net.springs.rest_length;
    }
  return {};
}

}  // namespace neurocloth
