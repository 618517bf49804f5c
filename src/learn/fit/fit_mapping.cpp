#include <algorithm>
#include <cmath>
#include <map>
#include <type_traits>
#include <variant>

#include "core/modules/module_set.h"
#include "learn/fit/fit_problem_impl.h"

namespace neurocloth {
using namespace fit_detail;

namespace fit_detail {
void set_spec_parameter(ModuleSpec& spec, const ParameterId& id, double value) {
  std::visit(
      [&](auto& s) {
        using T = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<T, WindSpec>) {
          if (id.parameter == ModuleParameter::velocity) s.velocity[id.axis] = value;
          if (id.parameter == ModuleParameter::drag) s.drag = value;
          if (id.parameter == ModuleParameter::lift) s.lift = value;
        } else if constexpr (std::is_same_v<T, AirDragSpec>) {
          if (id.parameter == ModuleParameter::rate) s.rate = value;
        } else if constexpr (std::is_same_v<T, BendingSpec>) {
          if (id.parameter == ModuleParameter::rigidity) s.rigidity = value;
        } else if constexpr (std::is_same_v<T, PlaneSpec> || std::is_same_v<T, BoxSpec> ||
                             std::is_same_v<T, SphereSpec> || std::is_same_v<T, CapsuleSpec> ||
                             std::is_same_v<T, CylinderSpec> || std::is_same_v<T, MeshSpec>) {
          if (id.parameter == ModuleParameter::friction) s.contact.friction = value;
        }
      },
      spec);
}
void set_path(ModuleSpec& spec, const Unknown& u, const Eigen::VectorXd& theta) {
  auto& keys = std::get<PinMotionSpec>(spec).keyframes;
  for (std::size_t j = 0; j < u.keys.size(); ++j)
    for (int axis = 0; axis < 3; ++axis)
      keys[u.keys[j]].second[axis] =
          theta[static_cast<Eigen::Index>(u.block.offset + 3 * j + std::size_t(axis))];
}
}  // namespace fit_detail

void FitProblem::Impl::apply(const Eigen::VectorXd& theta) {
  ClothNetwork& net = model.net;
  const ClothNetwork& b = base.net;
  // Modules start from the scene's; each unknown changes a copy of the one
  // before it, so two parameters of one module both hold.
  net.force_modules = b.force_modules;
  model.constraints = base.constraints;
  std::map<int, ModuleDeclaration> changed_constraints;  // declaration -> its changed copy
  if (words) {
    const MaterialSensitivity m = scene.fuzzy_material->rules->sensitivity(inputs_at(theta));
    material = m.derived.material;
    net.apply_material(material);
    d_material.clear();
    for (const Unknown& u : unknowns)
      if (u.target == Target::input)
        d_material.push_back(m.d_inputs[static_cast<std::size_t>(u.input)]);
  }
  for (const Unknown& u : unknowns) {
    auto value = [&](std::size_t e) {
      const double t = theta[static_cast<Eigen::Index>(u.block.offset + (u.per_element ? e : 0))];
      return u.block.log_space ? std::exp(t) : t;
    };
    for (std::size_t e = 0; e < u.elements.size(); ++e) {
      const auto k = static_cast<std::size_t>(u.elements[e]);
      switch (u.target) {
        case Target::stiffness:
          net.springs.stiffness[k] = value(e);
          break;
        case Target::viscosity:
          net.springs.damping[k] = value(e);
          break;
        case Target::node_mass:
          net.masses.inverse_mass[k] = 1.0 / (value(e) * (u.per_element ? 1.0 : b.mass_share[k]));
          break;
        case Target::rest_length:
          net.springs.rest_length[k] =
              u.per_element ? value(e) : value(e) * b.springs.rest_length[k];
          break;
        case Target::friction:
          net.masses.friction[k] = value(e);
          break;
        default:
          break;
      }
    }
    if (u.target == Target::force_module) {
      auto changed = net.force_modules[static_cast<std::size_t>(u.module)]->clone();
      changed->set_parameter(u.id, value(0));
      net.force_modules[static_cast<std::size_t>(u.module)] = std::move(changed);
    } else if (u.target == Target::constraint) {
      auto at = changed_constraints.try_emplace(
          u.declaration, scene.modules[static_cast<std::size_t>(u.declaration)]);
      set_spec_parameter(at.first->second.spec, u.id, value(0));
    } else if (u.target == Target::path) {
      auto at = changed_constraints.try_emplace(
          u.declaration, scene.modules[static_cast<std::size_t>(u.declaration)]);
      set_path(at.first->second.spec, u, theta);
    } else if (u.target == Target::initial_velocity) {
      const auto o = static_cast<Eigen::Index>(u.block.offset);
      const Vec3 v(theta[o], theta[o + 1], theta[o + 2]);
      ClothState s0 = start;
      for (std::size_t i = 0; i < s0.size(); ++i)
        if (b.masses.free[i] != 0) s0.set_velocity(i, v);
      if (rollout) rollout->set_initial(s0);
    }
  }
  // Constraints have no clone(): the scene's declaration, changed and rebuilt.
  for (const Unknown& u : unknowns)
    if (u.target == Target::constraint || u.target == Target::path) {
      ModuleSet one = build_modules({changed_constraints.at(u.declaration)}, scene.topology);
      model.constraints[static_cast<std::size_t>(u.module)] = std::move(one.constraints.front());
    }
}

// theta with every value brought inside its limit: the loss at theta is the
// loss there, flat beyond the limit (zero_outside).
Eigen::VectorXd FitProblem::Impl::inside(const Eigen::VectorXd& theta) const {
  Eigen::VectorXd in = theta;
  for (const Unknown& u : unknowns) {
    double lo = u.low, hi = u.high;
    if (u.block.log_space) {  // exp(log(x)) may round past x: step inside
      lo = u.low > 0 ? std::log(u.low) : -HUGE_VAL;
      hi = std::log(u.high);
      while (std::exp(lo) < u.low)
        lo = std::nextafter(lo, HUGE_VAL);
      while (std::exp(hi) > u.high)
        hi = std::nextafter(hi, -HUGE_VAL);
    }
    for (std::size_t e = 0; e < u.block.count; ++e) {
      double& t = in[static_cast<Eigen::Index>(u.block.offset + e)];
      t = std::clamp(t, lo, hi);
    }
  }
  return in;
}

// Beyond a limit the loss does not change: no gradient along a clamped unknown.
void FitProblem::Impl::zero_outside(const Eigen::VectorXd& theta, const Eigen::VectorXd& in,
                                    Eigen::VectorXd& gradient) const {
  for (Eigen::Index i = 0; i < theta.size(); ++i)
    if (in[i] != theta[i]) gradient[i] = 0;
}

// A path's offsets, every keyframe's (the fixed first one's from the scene),
// and where each fitted one sits in theta (-1: fixed).
namespace {
void path_offsets(const Unknown& u, const Scene& scene, const Eigen::VectorXd& theta,
                  std::vector<Vec3>& offsets, std::vector<Eigen::Index>& at) {
  const auto& keys =
      std::get<PinMotionSpec>(scene.modules[static_cast<std::size_t>(u.declaration)].spec)
          .keyframes;
  offsets.clear();
  at.assign(keys.size(), -1);
  for (const auto& k : keys)
    offsets.push_back(k.second);
  for (std::size_t j = 0; j < u.keys.size(); ++j) {
    at[u.keys[j]] = static_cast<Eigen::Index>(u.block.offset + 3 * j);
    offsets[u.keys[j]] = theta.segment<3>(at[u.keys[j]]);
  }
}
}  // namespace

double FitProblem::Impl::regulariser(const Eigen::VectorXd& theta, Eigen::VectorXd* grad) const {
  double r = 0;
  // A path: its second differences over the keyframes (a jerk costs, a
  // straight line at constant speed does not).
  const double sp = settings.path_smoothness;
  if (sp > 0) {
    std::vector<Vec3> o;
    std::vector<Eigen::Index> at;
    for (const Unknown& u : unknowns) {
      if (u.target != Target::path) continue;
      path_offsets(u, scene, theta, o, at);
      for (std::size_t k = 1; k + 1 < o.size(); ++k) {
        const Vec3 d = o[k - 1] - 2 * o[k] + o[k + 1];
        r += 0.5 * sp * d.squaredNorm();
        if (!grad) continue;
        const std::size_t idx[3] = {k - 1, k, k + 1};
        const double w[3] = {1, -2, 1};
        for (int q = 0; q < 3; ++q)
          if (at[idx[q]] >= 0) grad->segment<3>(at[idx[q]]) += sp * w[q] * d;
      }
    }
  }
  const double s = settings.smoothness;
  if (!(s > 0)) return r;
  for (const Unknown& u : unknowns)
    for (const auto& [i, j] : u.neighbours) {
      const auto a = static_cast<Eigen::Index>(u.block.offset + static_cast<std::size_t>(i));
      const auto c = static_cast<Eigen::Index>(u.block.offset + static_cast<std::size_t>(j));
      const double d = theta[a] - theta[c];
      r += 0.5 * s * d * d;
      if (grad) {
        (*grad)[a] += s * d;
        (*grad)[c] -= s * d;
      }
    }
  return r;
}

// dE/dtheta from dE/d(weight): theta = log(value) for log-space blocks, so
// dE/dtheta = value dE/dvalue.
void FitProblem::Impl::chain(const Eigen::VectorXd& theta, Eigen::VectorXd& grad) const {
  const RolloutGradients& g = gradients;
  const ClothNetwork& net = model.net;
  grad.setZero(static_cast<Eigen::Index>(size));
  std::size_t input = 0;
  for (const Unknown& u : unknowns) {
    if (u.target == Target::input) {
      grad[static_cast<Eigen::Index>(u.block.offset)] = input_gradient(d_material[input++]);
      continue;
    }
    const auto at = [&](std::size_t e) {
      return static_cast<Eigen::Index>(u.block.offset + (u.per_element ? e : 0));
    };
    for (std::size_t e = 0; e < u.elements.size(); ++e) {
      const auto k = static_cast<std::size_t>(u.elements[e]);
      switch (u.target) {
        case Target::stiffness:
          grad[at(e)] += g.springs.stiffness[k] * net.springs.stiffness[k];
          break;
        case Target::viscosity:
          grad[at(e)] += g.springs.damping[k] * net.springs.damping[k];
          break;
        case Target::node_mass:  // w = 1 / m: dE/dlog m = -w dE/dw
          grad[at(e)] -= g.inverse_mass[k] * net.masses.inverse_mass[k];
          break;
        case Target::rest_length:
          grad[at(e)] += g.springs.rest_length[k] * net.springs.rest_length[k];
          break;
        case Target::friction:
          grad[at(e)] += g.friction[k] * net.masses.friction[k];
          break;
        default:
          break;
      }
    }
    if (u.target == Target::path) {
      const std::vector<double>& d = g.constraints[static_cast<std::size_t>(u.module)];
      for (std::size_t j = 0; j < u.keys.size(); ++j)
        for (std::size_t axis = 0; axis < 3; ++axis)
          grad[static_cast<Eigen::Index>(u.block.offset + 3 * j + axis)] =
              d[kModuleParameterSlots + 3 * u.keys[j] + axis];
      continue;
    }
    if (u.target == Target::initial_velocity) {
      // A window (online) starts from the running cloth: no initial state to move.
      if (g.initial.size() != net.node_count()) continue;
      for (std::size_t i = 0; i < net.node_count(); ++i)
        if (net.masses.free[i] != 0) {
          grad[at(0)] += g.initial.vx[i];
          grad[at(0) + 1] += g.initial.vy[i];
          grad[at(0) + 2] += g.initial.vz[i];
        }
      continue;
    }
    if (u.target == Target::force_module || u.target == Target::constraint) {
      const auto m = static_cast<std::size_t>(u.module);
      const auto slot = static_cast<std::size_t>(module_slot(u.id.parameter, u.id.axis));
      const double d =
          u.target == Target::force_module ? g.force_modules[m][slot] : g.constraints[m][slot];
      grad[at(0)] = u.block.log_space ? d * std::exp(theta[at(0)]) : d;
    }
  }
}

std::map<std::string, double> FitProblem::Impl::inputs_at(const Eigen::VectorXd& theta) const {
  std::map<std::string, double> inputs = scene.fuzzy_material->inputs;
  const fuzzy::FuzzySystem& rules = scene.fuzzy_material->rules->system();
  for (const Unknown& u : unknowns)
    if (u.target == Target::input)
      inputs[rules.inputs[static_cast<std::size_t>(u.input)].name] =
          theta[static_cast<Eigen::Index>(u.block.offset)];
  return inputs;
}

// dE/d(input) from the weights' gradients and the material's derivatives d
// with respect to that input: every spring's stiffness and damping, every
// node's inverse mass (w = 1 / (m share): dw = -w dm / m) and friction.
double FitProblem::Impl::input_gradient(const Material& d) const {
  const RolloutGradients& g = gradients;
  const ClothNetwork& net = model.net;
  double sum = 0;
  for (std::size_t s = 0; s < net.spring_count(); ++s) {
    const SpringFamily f = net.springs.family[s];
    const double dk = f == SpringFamily::structural ? d.spring_constant
                      : f == SpringFamily::shear    ? d.shear_constant
                                                    : d.bend_constant;
    sum += g.springs.stiffness[s] * dk + g.springs.damping[s] * d.viscosity;
  }
  for (std::size_t i = 0; i < g.inverse_mass.size(); ++i)
    sum -= g.inverse_mass[i] * net.masses.inverse_mass[i] * d.node_mass / material.node_mass;
  for (std::size_t i = 0; i < g.friction.size(); ++i)
    sum += g.friction[i] * d.friction;
  return sum;
}

}  // namespace neurocloth
