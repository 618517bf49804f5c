#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>

#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "core/modules/module_set.h"
#include "learn/fit/fit_problem_impl.h"

namespace neurocloth {
using namespace fit_detail;
namespace {

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
    case ModuleParameter::rigidity:
      return limits::kBendingRigidity;
  }
  return {-HUGE_VAL, HUGE_VAL, "", ""};
}

// The smoothness term's pairs of neighbouring elements: 32 M pairs (256 MB),
// 18 per node of a grid with every family, so a cloth of a million nodes.
constexpr std::size_t kMaxNeighbourPairs = std::size_t(1) << 25;

// A module parameter's text: "wind.drag", "wind[1].velocity.x", "plane.friction".
struct ModuleParameterName {
  ModuleParameter parameter;
  int axis;
};
bool parse_module_parameter(const std::string& text, ModuleParameterName& out) {
  static const ModuleParameter all[] = {ModuleParameter::velocity, ModuleParameter::rate,
                                        ModuleParameter::drag,     ModuleParameter::lift,
                                        ModuleParameter::friction, ModuleParameter::rigidity};
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

}  // namespace

namespace fit_detail {
[[noreturn]] void refuse(const std::string& message) {
  throw InputError("command line", "--params", message);
}
}  // namespace fit_detail

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

void FitProblem::Impl::add_input(const std::string& name) {
  const std::string input = name.substr(std::string("input.").size());
  if (!scene.fuzzy_material)
    refuse("'" + name +
           "': the scene's material is given as numbers; input.NAME fits the inputs of a "
           "material in words (material.rules or material.preset)");
  const fuzzy::FuzzySystem& rules = scene.fuzzy_material->rules->system();
  const int i = rules.input_index(input);
  if (i < 0) {
    std::string names;
    for (const auto& v : rules.inputs)
      names += (names.empty() ? "input." : ", input.") + v.name;
    refuse("'" + name + "': the rule base " + scene.fuzzy_material->rules_path + " has no input '" +
           input + "' (its inputs: " + names + ")");
  }
  const fuzzy::LinguisticVariable& v = rules.inputs[static_cast<std::size_t>(i)];
  Unknown u;
  u.block = {name, size, 1, false, ""};
  u.target = Target::input;
  u.input = i;
  u.base = scene.fuzzy_material->inputs.at(input);
  // Outside its RANGE the rule base clamps an input: the loss is flat there.
  u.low = v.min;
  u.high = v.max;
  size += 1;
  unknowns.push_back(std::move(u));
}

// The built constraint a declaration made: constraints were sorted by phase.
int FitProblem::Impl::constraint_of(int declaration) const {
  ModuleSet one =
      build_modules({scene.modules[static_cast<std::size_t>(declaration)]}, scene.topology);
  for (std::size_t c = 0; c < base.constraints.size(); ++c)
    if (base.constraints[c]->declaration == one.constraints.front()->declaration &&
        base.constraints[c]->type() == std::string(one.constraints.front()->type()))
      return static_cast<int>(c);
  return -1;
}

void FitProblem::Impl::add_path(const std::string& name, int declaration) {
  const ModuleDeclaration& d = scene.modules[static_cast<std::size_t>(declaration)];
  const auto* spec = std::get_if<PinMotionSpec>(&d.spec);
  if (!spec || spec->keyframes.empty())
    refuse("'" + name + "': a path is fitted through a pin_motion's keyframes" +
           (spec ? " (this one is a sine: give it keyframes)" : ""));
  Unknown u;
  u.target = Target::path;
  u.declaration = declaration;
  u.module = constraint_of(declaration);
  for (std::size_t k = 0; k < spec->keyframes.size(); ++k) {
    if (k == 0 && spec->keyframes[0].first <= 0) continue;  // where the pins start
    u.keys.push_back(k);
    for (int axis = 0; axis < 3; ++axis)
      u.starts.push_back(spec->keyframes[k].second[axis]);
  }
  if (u.keys.empty())
    refuse("'" + name + "': its only keyframe is at t = 0, where the pins start: nothing to fit");
  u.block = {name, size, u.starts.size(), false, "m"};
  u.low = -1e4;  // the scene's limit on an offset (docs/scenes.md, pin_motion)
  u.high = 1e4;
  size += u.block.count;
  unknowns.push_back(std::move(u));
}

void FitProblem::Impl::add_initial_velocity() {
  Unknown u;
  u.target = Target::initial_velocity;
  u.block = {"initial_velocity", size, 3, false, "m/s"};
  u.starts = {scene.initial_velocity.x(), scene.initial_velocity.y(), scene.initial_velocity.z()};
  u.low = limits::kSpeed.low;
  u.high = limits::kSpeed.high;
  size += 3;
  unknowns.push_back(std::move(u));
  gradients.want_initial = true;
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
    // A measured material's constants come from its lab values and the
    // cloth's geometry (measured_material.h): one family number does not say
    // them. Its bending is a module parameter; its weights may be fitted one
    // per element.
    if (scene.measured_material && !pe &&
        (name == "spring_constant" || name == "shear_constant" || name == "bend_constant" ||
         name == "viscosity" || name == "node_mass" || name == "friction"))
      refuse("'" + name +
             "': the material is measured (material.measured): fit bending.rigidity, or the "
             "weights one per element (--per-element)");
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
    } else if (name.rfind("input.", 0) == 0) {
      add_input(name);
    } else if (name == "initial_velocity") {
      add_initial_velocity();
    } else {
      // MODULE.PARAMETER: the module named as the window names it ("wind", "wind[1]").
      const auto dot = name.find('.');
      int declaration = -1;
      if (dot != std::string::npos)
        for (std::size_t d = 0; d < module_names.modules.size(); ++d)
          if (module_name(module_names, static_cast<int>(d)) == name.substr(0, dot))
            declaration = static_cast<int>(d);
      if (declaration >= 0 && name.substr(dot + 1) == "keyframes") {
        add_path(name, declaration);
        continue;
      }
      ModuleParameterName p{};
      if (declaration < 0 || !parse_module_parameter(name.substr(dot + 1), p))
        refuse("unknown parameter '" + name +
               "' (fit knows spring_constant, shear_constant, bend_constant, viscosity, node_mass, "
               "rest_length, friction, module parameters such as wind.velocity.x, wind.drag, "
               "wind.lift, air_drag.rate, bending.rigidity, plane.friction, a material in words' "
               "inputs as "
               "input.NAME, a pin_motion's keyframes as pin_motion.keyframes, and "
               "initial_velocity)");
      // Find the built module of that declaration: force modules keep
      // declaration order; constraints were sorted by phase.
      Unknown u;
      u.id = ParameterId::module(declaration, p.parameter, p.axis);
      u.declaration = declaration;
      const std::string& type = scene.modules[static_cast<std::size_t>(declaration)].type;
      const bool is_force =
          is_force_module(scene.modules[static_cast<std::size_t>(declaration)].spec);
      int index = 0;
      for (int d = 0; d < declaration; ++d)
        index += is_force_module(scene.modules[static_cast<std::size_t>(d)].spec) == is_force;
      std::optional<double> value;
      if (is_force) {
        u.target = Target::force_module;
        u.module = index;
        value = base.net.force_modules[static_cast<std::size_t>(index)]->parameter(u.id);
      } else {
        u.target = Target::constraint;
        u.module = constraint_of(declaration);
        if (u.module >= 0)
          value = base.constraints[static_cast<std::size_t>(u.module)]->parameter(u.id);
      }
      if (!value)
        refuse("'" + name + "': module '" + type + "' has no such parameter" +
               (p.parameter == ModuleParameter::friction
                    ? " (it uses the material's friction: fit 'friction')"
                    : ""));
      u.block = {name, size, 1, p.parameter != ModuleParameter::velocity,
                 p.parameter == ModuleParameter::velocity   ? "m/s"
                 : p.parameter == ModuleParameter::rate     ? "1/s"
                 : p.parameter == ModuleParameter::rigidity ? "N m"
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
  // The inputs set every material weight: nothing else may set them too.
  words = std::any_of(unknowns.begin(), unknowns.end(),
                      [](const Unknown& u) { return u.target == Target::input; });
  if (words) {
    for (const Unknown& u : unknowns)
      if (u.target == Target::stiffness || u.target == Target::viscosity ||
          u.target == Target::node_mass || u.target == Target::friction)
        refuse("'" + u.block.name +
               "' and the rule base's inputs both set the material: fit one or the other");
    if (scene.element_weights)
      refuse(
          "the scene's element_weights replace the weights its material in words gives: fit "
          "input.* on a scene without them");
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

}  // namespace neurocloth
