#include "fit_problem.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <type_traits>
#include <variant>

#include "input_error.h"
#include "modules/module_set.h"
#include "parameter_id.h"
#include "physical_limits.h"
#include "rollout.h"

namespace neurocloth {
namespace {

// What a block of theta sets in the model.
enum class Target {
  stiffness,     // spring_constant / shear_constant / bend_constant: b1 of `elements`
  viscosity,     // b2 of `elements` (every spring)
  node_mass,     // 1 / w of `elements` (every node), times the node's mass share
  rest_length,   // L of `elements`: a scale on the scene's lengths, or each length
  friction,      // the material's Coulomb coefficient, every node
  force_module,  // a parameter of net.force_modules[module]
  constraint,    // a parameter of constraints[module]
};

struct Unknown {
  FitBlock block;
  Target target;
  bool per_element = false;
  std::vector<std::int32_t> elements;  // springs or nodes it sets
  int module = -1;                     // index into the model's force modules or constraints
  int declaration = -1;                // the module's index in the scene's declarations
  ParameterId id;                      // module parameter (parameter and axis)
  double base = 1;                     // family value at the start (rest length: 1, a scale)
  // The scene's limits on the value (physical_limits.h): a fitted value stays
  // inside them, so FITTED.json loads (Impl::inside).
  double low = -HUGE_VAL, high = HUGE_VAL;
  // Per-element blocks: pairs of neighbouring elements the smoothness term ties.
  std::vector<std::pair<std::int32_t, std::int32_t>> neighbours;
};

// The scene's limit on what a target sets (module parameters: module_limit).
Limit target_limit(Target t) {
  switch (t) {
    case Target::stiffness:
      return limits::kStiffness;
    case Target::viscosity:
      return limits::kViscosity;
    case Target::node_mass:
      return limits::kNodeMass;
    case Target::rest_length:
      return limits::kRestLength;
    case Target::friction:
      return limits::kFriction;
    default:
      return {-HUGE_VAL, HUGE_VAL, "", ""};
  }
}

Limit module_limit(ModuleParameter p) {
  switch (p) {
    case ModuleParameter::velocity:
      return limits::kSpeed;
    case ModuleParameter::rate:
      return limits::kRate;
    case ModuleParameter::drag:
    case ModuleParameter::lift:
      return limits::kCoefficient;
    case ModuleParameter::friction:
      return limits::kFriction;
  }
  return {-HUGE_VAL, HUGE_VAL, "", ""};
}

// The smoothness term's pairs of neighbouring elements: 32 M pairs (256 MB),
// 18 per node of a grid with every family, so a cloth of a million nodes.
constexpr std::size_t kMaxNeighbourPairs = std::size_t(1) << 25;

[[noreturn]] void refuse(const std::string& message) {
  throw InputError("command line", "--params", message);
}

// A module parameter's text: "wind.drag", "wind[1].velocity.x", "plane.friction".
struct ModuleParameterName {
  ModuleParameter parameter;
  int axis;
};
bool parse_module_parameter(const std::string& text, ModuleParameterName& out) {
  static const ModuleParameter all[] = {ModuleParameter::velocity, ModuleParameter::rate,
                                        ModuleParameter::drag, ModuleParameter::lift,
                                        ModuleParameter::friction};
  for (ModuleParameter p : all) {
    const std::string name = module_parameter_name(p);
    if (p == ModuleParameter::velocity) {
      for (int axis = 0; axis < 3; ++axis)
        if (text == name + "." + "xyz"[axis]) {
          out = {p, axis};
          return true;
        }
    } else if (text == name) {
      out = {p, -1};
      return true;
    }
  }
  return false;
}

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
        } else if constexpr (std::is_same_v<T, PlaneSpec> || std::is_same_v<T, BoxSpec> ||
                             std::is_same_v<T, SphereSpec> || std::is_same_v<T, CapsuleSpec>) {
          if (id.parameter == ModuleParameter::friction) s.contact.friction = value;
        }
      },
      spec);
}

}  // namespace

struct FitProblem::Impl {
  Scene scene;
  FitSettings settings;
  RolloutModel base;   // the scene's model
  RolloutModel model;  // the model at the last theta
  std::vector<Unknown> unknowns;
  std::vector<FitBlock> blocks;
  std::size_t size = 0;
  std::unique_ptr<Rollout> rollout;
  StepPlan steps;                   // the whole run's
  ObservationPlan observed;         // the whole run's
  std::vector<double> frame_times;  // the reference's, one per observed frame
  RolloutGradients gradients;
  double duration = 0;

  void build_model();
  void parse_parameters();
  void add_family(const std::string& name, Target target, std::vector<std::int32_t> elements,
                  double value, const std::string& unit, bool per_element);
  void plan(const ReferenceMotion& reference);
  void apply(const Eigen::VectorXd& theta);
  Eigen::VectorXd inside(const Eigen::VectorXd& theta) const;
  void zero_outside(const Eigen::VectorXd& theta, const Eigen::VectorXd& in,
                    Eigen::VectorXd& gradient) const;
  double regulariser(const Eigen::VectorXd& theta, Eigen::VectorXd* gradient) const;
  void chain(const Eigen::VectorXd& theta, Eigen::VectorXd& gradient) const;
};

void FitProblem::Impl::build_model() {
  const SolverSettings& s = scene.solver;
  if (s.integrator != IntegratorKind::network)
    throw InputError(scene.path, "solver.integrator",
                     std::string("fit: integrator '") + to_string(s.integrator) +
                         "' has no adjoint (fit runs the network integrator, fixed or adaptive)");
  base.net = scene.build_network();
  // The scene's modules in the order Scene::make_simulation runs them, and
  // which declaration each one came from.
  std::vector<std::pair<int, std::shared_ptr<const ConstraintModule>>> constraints;
  for (std::size_t d = 0; d < scene.modules.size(); ++d) {
    ModuleSet one = build_modules({scene.modules[d]}, scene.topology);
    for (auto& f : one.forces) {
      if (!f->has_adjoint())
        throw InputError(scene.path, "modules[" + std::to_string(d) + "]",
                         std::string("fit: module '") + f->type() + "' has no adjoint");
      base.net.force_modules.push_back(std::move(f));
    }
    for (auto& c : one.constraints) {
      if (!c->has_adjoint() || c->make_state())
        throw InputError(scene.path, "modules[" + std::to_string(d) + "]",
                         std::string("fit: module '") + c->type() + "' has no adjoint");
      constraints.emplace_back(static_cast<int>(d), std::move(c));
    }
  }
  std::stable_sort(constraints.begin(), constraints.end(), [](const auto& a, const auto& b) {
    return a.second->phase() < b.second->phase();
  });
  for (auto& c : constraints)
    base.constraints.push_back(c.second);
  model = base;
}

void FitProblem::Impl::add_family(const std::string& name, Target target,
                                  std::vector<std::int32_t> elements, double value,
                                  const std::string& unit, bool per_element) {
  if (elements.empty()) refuse("'" + name + "': nothing in this scene has it");
  if (!(value > 0) || !std::isfinite(value))
    refuse("'" + name + "' is " + std::to_string(value) +
           " in the scene: a fit in log space needs a start > 0");
  Unknown u;
  u.block = {name, size, per_element ? elements.size() : 1, true, unit};
  u.target = target;
  u.per_element = per_element;
  u.elements = std::move(elements);
  u.base = value;
  const Limit limit = target_limit(target);
  u.low = limit.low;
  u.high = limit.high;
  size += u.block.count;
  unknowns.push_back(std::move(u));
}

void FitProblem::Impl::parse_parameters() {
  const ClothNetwork& net = base.net;
  const Material& mat = scene.material;
  const bool pe = settings.per_element;
  std::set<std::string> seen;
  const std::vector<std::string>& names = settings.params;
  if (names.empty()) refuse("names no parameter");
  auto listed = [&](const char* n) {
    return std::find(names.begin(), names.end(), n) != names.end();
  };
  std::vector<std::int32_t> all_springs(net.spring_count()), all_nodes(net.node_count());
  for (std::size_t s = 0; s < all_springs.size(); ++s)
    all_springs[s] = static_cast<std::int32_t>(s);
  for (std::size_t i = 0; i < all_nodes.size(); ++i)
    all_nodes[i] = static_cast<std::int32_t>(i);
  const ParameterNames module_names = parameter_names(scene);

  for (const std::string& name : names) {
    if (!seen.insert(name).second) refuse("'" + name + "' is listed twice");
    if (name == "spring_constant" || name == "shear_constant" || name == "bend_constant") {
      // A family's springs: its own, and those of a family that follows the
      // spring constant (shear_constant < 0) unless that one is fitted itself.
      std::vector<std::int32_t> springs;
      for (std::size_t s = 0; s < net.spring_count(); ++s) {
        const SpringFamily f = net.springs.family[s];
        bool mine = false;
        if (name == "spring_constant")
          mine =
              f == SpringFamily::structural ||
              (f == SpringFamily::shear && mat.shear_constant < 0 && !listed("shear_constant")) ||
              (f == SpringFamily::bend && mat.bend_constant < 0 && !listed("bend_constant"));
        else if (name == "shear_constant")
          mine = f == SpringFamily::shear;
        else
          mine = f == SpringFamily::bend;
        if (mine) springs.push_back(static_cast<std::int32_t>(s));
      }
      const double value = name == "spring_constant"  ? mat.spring_constant
                           : name == "shear_constant" ? mat.shear()
                                                      : mat.bend();
      add_family(name, Target::stiffness, std::move(springs), value, "N/m", pe);
    } else if (name == "viscosity") {
      add_family(name, Target::viscosity, all_springs, mat.viscosity, "N s/m", pe);
    } else if (name == "node_mass") {
      add_family(name, Target::node_mass, all_nodes, mat.node_mass, "kg", pe);
    } else if (name == "rest_length") {
      add_family(name, Target::rest_length, all_springs, 1.0, pe ? "m" : "x scene", pe);
      if (pe) {
        unknowns.back().base = 0;  // per element: each spring's own length
      } else {                     // a scale: the longest spring stays inside the limit
        double longest = 0;
        for (double l : net.springs.rest_length)
          longest = std::max(longest, l);
        unknowns.back().low = 0;
        unknowns.back().high = longest > 0 ? limits::kRestLength.high / longest : HUGE_VAL;
      }
    } else if (name == "friction") {
      bool used = false;
      for (const auto& c : base.constraints)
        used |= c->phase() == ConstraintModule::contact &&
                !c->parameter(ParameterId::module(0, ModuleParameter::friction, -1)).has_value();
      if (!used) refuse("'friction': no collider in this scene uses the material's friction");
      add_family(name, Target::friction, all_nodes, mat.friction, "", false);
    } else {
      // MODULE.PARAMETER: the module named as the window names it ("wind", "wind[1]").
      const auto dot = name.find('.');
      int declaration = -1;
      if (dot != std::string::npos)
        for (std::size_t d = 0; d < module_names.modules.size(); ++d)
          if (module_name(module_names, static_cast<int>(d)) == name.substr(0, dot))
            declaration = static_cast<int>(d);
      ModuleParameterName p{};
      if (declaration < 0 || !parse_module_parameter(name.substr(dot + 1), p))
        refuse("unknown parameter '" + name +
               "' (fit knows spring_constant, shear_constant, bend_constant, viscosity, node_mass, "
               "rest_length, friction, and module parameters such as wind.velocity.x, wind.drag, "
               "wind.lift, air_drag.rate, plane.friction)");
      // Find the built module of that declaration: force modules keep
      // declaration order; constraints were sorted by phase.
      Unknown u;
      u.id = ParameterId::module(declaration, p.parameter, p.axis);
      u.declaration = declaration;
      const std::string& type = scene.modules[static_cast<std::size_t>(declaration)].type;
      const bool is_force = type == "wind" || type == "air_drag";
      int index = 0;
      for (int d = 0; d < declaration; ++d) {
        const std::string& t = scene.modules[static_cast<std::size_t>(d)].type;
        index += (t == "wind" || t == "air_drag") == is_force;
      }
      std::optional<double> value;
      if (is_force) {
        u.target = Target::force_module;
        u.module = index;
        value = base.net.force_modules[static_cast<std::size_t>(index)]->parameter(u.id);
      } else {
        u.target = Target::constraint;
        // The index-th constraint by declaration: find it after the sort.
        ModuleSet one =
            build_modules({scene.modules[static_cast<std::size_t>(declaration)]}, scene.topology);
        for (std::size_t c = 0; c < base.constraints.size(); ++c)
          if (base.constraints[c]->declaration == one.constraints.front()->declaration &&
              base.constraints[c]->type() == std::string(one.constraints.front()->type()))
            u.module = static_cast<int>(c);
        if (u.module >= 0)
          value = base.constraints[static_cast<std::size_t>(u.module)]->parameter(u.id);
      }
      if (!value)
        refuse("'" + name + "': module '" + type + "' has no such parameter" +
               (p.parameter == ModuleParameter::friction
                    ? " (it uses the material's friction: fit 'friction')"
                    : ""));
      u.block = {name, size, 1, p.parameter != ModuleParameter::velocity,
                 p.parameter == ModuleParameter::velocity ? "m/s"
                 : p.parameter == ModuleParameter::rate   ? "1/s"
                                                          : ""};
      if (u.block.log_space && !(*value > 0))
        refuse("'" + name + "' is " + std::to_string(*value) +
               " in the scene: a fit in log space needs a start > 0");
      u.base = *value;
      u.low = module_limit(p.parameter).low;
      u.high = module_limit(p.parameter).high;
      size += 1;
      unknowns.push_back(std::move(u));
    }
  }
  // Neighbours for the smoothness term: springs of one family that share a
  // node; nodes joined by a structural spring.
  // Only a fit with a regulariser needs them; their number grows with the
  // square of a node's springs, so it is counted before anything is stored
  // (a fan of 100000 triangles round one vertex would ask for 40 GB).
  std::size_t pairs = 0;
  for (Unknown& u : unknowns) {
    if (!u.per_element || !(settings.smoothness > 0)) continue;
    if (u.target == Target::node_mass) {
      pairs += net.spring_count();
      continue;
    }
    std::vector<std::array<std::size_t, 3>> per_family(net.node_count());  // springs at a node
    for (const std::int32_t spring : u.elements) {
      const auto f = static_cast<std::size_t>(net.springs.family[spring]);
      ++per_family[static_cast<std::size_t>(net.springs.node_a[spring])][f];
      ++per_family[static_cast<std::size_t>(net.springs.node_b[spring])][f];
    }
    for (const auto& counts : per_family)
      for (const std::size_t k : counts)
        pairs += k > 1 ? k * (k - 1) / 2 : 0;
  }
  if (pairs > kMaxNeighbourPairs)
    throw InputError("command line", "--smoothness",
                     "the regulariser would tie " + std::to_string(pairs) +
                         " pairs of neighbouring elements (nodes with very many springs), more "
                         "than " +
                         std::to_string(kMaxNeighbourPairs) +
                         ": fit this cloth without --smoothness");
  for (Unknown& u : unknowns) {
    if (!u.per_element || !(settings.smoothness > 0)) continue;
    if (u.target == Target::node_mass) {
      for (std::size_t s = 0; s < net.spring_count(); ++s)
        if (net.springs.family[s] == SpringFamily::structural)
          u.neighbours.emplace_back(net.springs.node_a[s], net.springs.node_b[s]);
      continue;
    }
    std::map<std::int32_t, std::int32_t> element_of;  // spring -> element
    for (std::size_t e = 0; e < u.elements.size(); ++e)
      element_of[u.elements[e]] = static_cast<std::int32_t>(e);
    std::vector<std::vector<std::int32_t>> at_node(net.node_count());
    for (const auto& [spring, e] : element_of) {
      at_node[static_cast<std::size_t>(net.springs.node_a[spring])].push_back(spring);
      at_node[static_cast<std::size_t>(net.springs.node_b[spring])].push_back(spring);
    }
    for (const auto& list : at_node)
      for (std::size_t i = 0; i < list.size(); ++i)
        for (std::size_t j = i + 1; j < list.size(); ++j)
          if (net.springs.family[list[i]] == net.springs.family[list[j]])
            u.neighbours.emplace_back(element_of[list[i]], element_of[list[j]]);
  }
  for (const Unknown& u : unknowns)
    blocks.push_back(u.block);
}

void FitProblem::Impl::plan(const ReferenceMotion& ref) {
  if (ref.frames.empty()) throw InputError(ref.path, "frames", "the reference has no frames");
  const std::size_t n = base.net.node_count();
  duration = ref.frames.back().time;
  if (!(duration > 0))
    throw InputError(ref.path, "time", "the reference ends at t = 0: nothing to fit to");
  // A fit runs the scene to the last frame many times: a reference whose time
  // runs to years would never finish (or allocate a plan of that many steps).
  if (!(duration / scene.solver.dt <= static_cast<double>(kMaxFitSteps)))
    throw InputError(ref.path, "time",
                     "the reference ends at t = " + show_number(duration) +
                         " s: " + show_number(duration / scene.solver.dt) +
                         " steps of the scene's dt; a fit runs at most 1e7");
  StepPlan steps;
  try {
    steps = plan_steps(scene, duration);
  } catch (const std::runtime_error& e) {
    throw InputError(scene.path, "solver", std::string("fit: ") + e.what());
  }
  ObservationPlan obs;
  for (const ReferenceFrame& f : ref.frames) {
    if (!(f.time >= 0))
      throw InputError(ref.path, "time", "a frame before the scene's start (t < 0)");
    ObservationPlan::Frame fr;
    const auto it = std::upper_bound(steps.start.begin(), steps.start.end(), f.time);
    fr.step =
        it == steps.start.begin() ? 0 : static_cast<std::size_t>(it - steps.start.begin()) - 1;
    fr.step = std::min(fr.step, steps.count() - 1);
    fr.alpha = std::clamp((f.time - steps.start[fr.step]) / steps.size[fr.step], 0.0, 1.0);
    fr.first = obs.nodes.size();
    fr.count = f.nodes.size();
    for (std::size_t k = 0; k < f.nodes.size(); ++k) {
      const std::int32_t file_node = f.nodes[k];
      if (file_node < 0 || static_cast<std::size_t>(file_node) >= n)
        throw InputError(ref.path, "node",
                         "node " + std::to_string(file_node) + " is not in the scene (it has " +
                             std::to_string(n) + " nodes)");
      obs.nodes.push_back(scene.topology.numbering.node(file_node));
      obs.targets.push_back(f.positions[k]);
    }
    obs.frames.push_back(fr);
    frame_times.push_back(f.time);
  }
  this->steps = steps;
  observed = obs;
  rollout = std::make_unique<Rollout>(scene.initial_state(), std::move(steps), std::move(obs),
                                      settings.tape_budget_bytes);
}

void FitProblem::Impl::apply(const Eigen::VectorXd& theta) {
  ClothNetwork& net = model.net;
  const ClothNetwork& b = base.net;
  // Modules start from the scene's; each unknown changes a copy of the one
  // before it, so two parameters of one module both hold.
  net.force_modules = b.force_modules;
  model.constraints = base.constraints;
  std::map<int, ModuleDeclaration> changed_constraints;  // declaration -> its changed copy
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
    }
  }
  // Constraints have no clone(): the scene's declaration, changed and rebuilt.
  for (const Unknown& u : unknowns)
    if (u.target == Target::constraint) {
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

double FitProblem::Impl::regulariser(const Eigen::VectorXd& theta, Eigen::VectorXd* grad) const {
  const double s = settings.smoothness;
  if (!(s > 0)) return 0;
  double r = 0;
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
  for (const Unknown& u : unknowns) {
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
    if (u.target == Target::force_module || u.target == Target::constraint) {
      const auto& slots = u.target == Target::force_module ? g.force_modules : g.constraints;
      const double d = slots[static_cast<std::size_t>(u.module)]
                            [static_cast<std::size_t>(module_slot(u.id.parameter, u.id.axis))];
      grad[at(0)] = u.block.log_space ? d * std::exp(theta[at(0)]) : d;
    }
  }
}

FitProblem::FitProblem(const Scene& scene, const ReferenceMotion& reference,
                       const FitSettings& settings)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.scene = scene;
  m.settings = settings;
  if (!(settings.smoothness >= 0) || !std::isfinite(settings.smoothness))
    throw InputError("command line", "--smoothness", "must be a finite number >= 0");
  m.build_model();
  m.plan(reference);
  m.parse_parameters();
  // A per-element weight of 0 (a side file may hold one: a spring without
  // stiffness, damping or length) has no logarithm to start from.
  const Eigen::VectorXd start = initial();
  for (const Unknown& u : m.unknowns)
    for (std::size_t e = 0; e < u.block.count; ++e)
      if (!std::isfinite(start[static_cast<Eigen::Index>(u.block.offset + e)]))
        refuse("'" + u.block.name + "' of " +
               (u.target == Target::node_mass ? "node " : "spring ") +
               std::to_string(u.elements[e]) +
               " is 0 in the scene: a fit in log space needs every start > 0 (leave it out, or "
               "fit it per family)");
  bool masses = false, friction = false;
  for (const Unknown& u : m.unknowns) {
    masses |= u.target == Target::node_mass;
    friction |= u.target == Target::friction;
  }
  // Only what a fit asks for is collected (the inverse mass needs the forces again).
  if (masses) m.gradients.inverse_mass.assign(m.base.net.node_count(), 0.0);
  if (friction) m.gradients.friction.assign(m.base.net.node_count(), 0.0);
}

FitProblem::~FitProblem() = default;
FitProblem::FitProblem(FitProblem&&) noexcept = default;

std::size_t FitProblem::size() const {
  return impl_->size;
}
const std::vector<FitBlock>& FitProblem::blocks() const {
  return impl_->blocks;
}

Eigen::VectorXd FitProblem::initial() const {
  Eigen::VectorXd theta(static_cast<Eigen::Index>(impl_->size));
  const ClothNetwork& net = impl_->base.net;
  for (const Unknown& u : impl_->unknowns) {
    for (std::size_t e = 0; e < u.block.count; ++e) {
      double v = u.base;
      if (u.per_element) {
        const auto k = static_cast<std::size_t>(u.elements[e]);
        if (u.target == Target::stiffness) v = net.springs.stiffness[k];
        if (u.target == Target::viscosity) v = net.springs.damping[k];
        if (u.target == Target::node_mass) v = net.mass(k);
        if (u.target == Target::rest_length) v = net.springs.rest_length[k];
      }
      theta[static_cast<Eigen::Index>(u.block.offset + e)] = u.block.log_space ? std::log(v) : v;
    }
  }
  return theta;
}

Eigen::VectorXd FitProblem::inside_limits(const Eigen::VectorXd& theta) const {
  return impl_->inside(theta);
}

Eigen::VectorXd FitProblem::values(const Eigen::VectorXd& theta_in) const {
  const Eigen::VectorXd theta = impl_->inside(theta_in);
  Eigen::VectorXd v = theta;
  for (const FitBlock& b : impl_->blocks)
    if (b.log_space)
      for (std::size_t e = 0; e < b.count; ++e)
        v[static_cast<Eigen::Index>(b.offset + e)] =
            std::exp(theta[static_cast<Eigen::Index>(b.offset + e)]);
  return v;
}

double FitProblem::loss(const Eigen::VectorXd& theta, Eigen::VectorXd* gradient) {
  Impl& m = *impl_;
  if (static_cast<std::size_t>(theta.size()) != m.size)
    throw std::invalid_argument("FitProblem::loss: theta has the wrong size");
  if (!theta.allFinite()) {
    if (gradient) gradient->setConstant(static_cast<Eigen::Index>(m.size), std::nan(""));
    return std::nan("");
  }
  const Eigen::VectorXd in = m.inside(theta);
  m.apply(in);
  const double data = m.rollout->run(m.model, gradient ? &m.gradients : nullptr);
  if (!gradient) return data + m.regulariser(in, nullptr);
  if (!std::isfinite(data)) {
    gradient->setConstant(static_cast<Eigen::Index>(m.size), std::nan(""));
    return data;
  }
  m.chain(in, *gradient);
  const double r = m.regulariser(in, gradient);
  m.zero_outside(theta, in, *gradient);
  return data + r;
}

double FitProblem::window_loss(const Eigen::VectorXd& theta, const ClothState& state,
                               std::size_t first, std::size_t count, Eigen::VectorXd* gradient,
                               ClothState* end) {
  Impl& m = *impl_;
  if (first >= m.steps.count() || count == 0)
    throw std::invalid_argument("FitProblem::window_loss: no such steps");
  count = std::min(count, m.steps.count() - first);
  const Eigen::VectorXd in = m.inside(theta);
  m.apply(in);
  Rollout window(state, window_of(m.steps, first, count), window_of(m.observed, first, count),
                 m.settings.tape_budget_bytes);
  const double data = window.run(m.model, gradient ? &m.gradients : nullptr);
  if (end) *end = window.final_state();
  if (gradient) {
    if (std::isfinite(data)) {
      m.chain(in, *gradient);
      m.zero_outside(theta, in, *gradient);
    } else
      gradient->setConstant(static_cast<Eigen::Index>(m.size), std::nan(""));
  }
  return data;
}

std::size_t FitProblem::window_observations(std::size_t first, std::size_t count) const {
  std::size_t n = 0;
  for (const ObservationPlan::Frame& f : impl_->observed.frames)
    if (f.step >= first && f.step < first + count) n += f.count;
  return n;
}

std::size_t FitProblem::step_count() const {
  return impl_->steps.count();
}
double FitProblem::step_time(std::size_t k) const {
  return impl_->steps.start.at(k);
}
ClothState FitProblem::initial_state() const {
  return impl_->scene.initial_state();
}

bool FitProblem::reference_state(double t, ClothState& state) const {
  const Impl& m = *impl_;
  const std::vector<double>& ft = m.frame_times;
  const std::size_t n = m.base.net.node_count();
  if (ft.size() < 2 || !(t >= ft.front()) || !(t <= ft.back())) return false;
  // Frame f observes every node, in the order frame 0 lists them.
  const auto full = [&](std::size_t f) {
    const ObservationPlan::Frame& fr = m.observed.frames[f];
    if (fr.count != n) return false;
    const ObservationPlan::Frame& first = m.observed.frames[0];
    return first.count == n && std::equal(m.observed.nodes.begin() + std::ptrdiff_t(fr.first),
                                          m.observed.nodes.begin() + std::ptrdiff_t(fr.first + n),
                                          m.observed.nodes.begin() + std::ptrdiff_t(first.first));
  };
  const auto at = [&](std::size_t f, std::size_t k) -> Vec3 {
    return m.observed.targets[m.observed.frames[f].first + k];
  };
  std::size_t f = static_cast<std::size_t>(std::upper_bound(ft.begin(), ft.end(), t) - ft.begin());
  f = std::min(std::max<std::size_t>(f, 1), ft.size() - 1);  // frames f-1 and f bracket t
  if (!full(f - 1) || !full(f)) return false;
  // Velocity at a frame: central difference where both neighbours are full
  // (second order), else one-sided.
  const auto velocity = [&](std::size_t g, std::size_t k) -> Vec3 {
    const std::size_t lo = g > 0 && full(g - 1) ? g - 1 : g;
    const std::size_t hi = g + 1 < ft.size() && full(g + 1) ? g + 1 : g;
    return (at(hi, k) - at(lo, k)) / (ft[hi] - ft[lo]);
  };
  const double w = (t - ft[f - 1]) / (ft[f] - ft[f - 1]);
  ClothState s(n);
  const ObservationPlan::Frame& first = m.observed.frames[f - 1];
  for (std::size_t k = 0; k < n; ++k) {
    const auto i = static_cast<std::size_t>(m.observed.nodes[first.first + k]);
    s.set_position(i, (1 - w) * at(f - 1, k) + w * at(f, k));
    s.set_velocity(i, (1 - w) * velocity(f - 1, k) + w * velocity(f, k));
  }
  state = std::move(s);
  return true;
}

double FitProblem::rms_error(const Eigen::VectorXd& theta) {
  Impl& m = *impl_;
  m.apply(m.inside(theta));
  const double data = m.rollout->run(m.model, nullptr);
  return std::sqrt(2.0 * data / static_cast<double>(std::max<std::size_t>(1, observations())));
}

std::size_t FitProblem::observations() const {
  return impl_->rollout ? impl_->rollout->compared().size() : 0;
}
double FitProblem::duration() const {
  return impl_->duration;
}
std::size_t FitProblem::peak_tape_bytes() const {
  return impl_->rollout->peak_tape_bytes();
}

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
    } else if (u.declaration >= 0) {
      set_spec_parameter(s.modules[static_cast<std::size_t>(u.declaration)].spec, u.id, v);
    }
  }
  s.fuzzy_material.reset();
  return s;
}

MaterialWeights FitProblem::element_weights(const Eigen::VectorXd& theta) const {
  if (!impl_->settings.per_element) return {};
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
