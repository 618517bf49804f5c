#pragma once
// The activation of the paper's position-force neuron: elongation -> force per
// unit stiffness. The stiffness itself is the force neuron's weight b1 (see
// spring_layer.h), so every spring function shares the same learnable weights.
#include <algorithm>
#include <string>

namespace neurocloth {

enum class SpringFunctionKind { linear, stiffening };

struct SpringFunction {
  SpringFunctionKind kind = SpringFunctionKind::linear;
  // stiffening: beyond this strain (elongation / rest length) the spring is
  // `stiffening_factor` times stiffer — woven cloth is soft until its yarns straighten.
  double strain_threshold = 0.1;
  double stiffening_factor = 10.0;

  // phi(e): force per unit stiffness for elongation e = l - L0 (continuous in e).
  double force(double e, double rest_length) const {
    if (kind == SpringFunctionKind::linear) return e;
    const double beyond = std::max(0.0, e - strain_threshold * rest_length);
    return e + (stiffening_factor - 1.0) * beyond;
  }
  // dphi/de, used by the implicit integrator's linearisation.
  double slope(double e, double rest_length) const {
    if (kind == SpringFunctionKind::linear) return 1.0;
    return e > strain_threshold * rest_length ? stiffening_factor : 1.0;
  }
  // Integral of phi from 0 to e: the spring's potential energy per unit stiffness.
  double energy(double e, double rest_length) const {
    const double base = 0.5 * e * e;
    if (kind == SpringFunctionKind::linear) return base;
    const double beyond = std::max(0.0, e - strain_threshold * rest_length);
    return base + 0.5 * (stiffening_factor - 1.0) * beyond * beyond;
  }
  // Largest slope anywhere: bounds the spring's contribution to omega_max.
  double max_slope() const {
    return kind == SpringFunctionKind::linear ? 1.0 : std::max(1.0, stiffening_factor);
  }
};

const char* to_string(SpringFunctionKind k);

}  // namespace neurocloth
