#pragma once
// The name of a number that may change while a scene runs (a viewer's slider,
// a window script's "set", and the weights learning adapts). Text is parsed
// into a ParameterId once, where it comes in; everything past that point
// (commands, ranges, the live scene, modules) compares ids, never strings.
//
// Input and module ids are indices, so they mean something only together with
// the ParameterNames of the scene they were parsed against.
#include <optional>
#include <string>
#include <vector>

namespace neurocloth {

// A number a module lets change between steps (SceneModule::set_parameter).
// A vector is changed one axis at a time; a scalar has axis -1. Only the wind's
// velocity is a live control in the window; learning may adapt all of them.
enum class ModuleParameter {
  velocity,  // wind: the mean air velocity, m/s
  rate,      // air_drag: 1/s
  drag,      // wind: drag coefficient
  lift,      // wind: lift coefficient
  friction,  // a collider's own kinetic Coulomb coefficient
  rigidity,  // bending: the bending rigidity, N m
};
// velocity x, y, z, rate, drag, lift, friction, rigidity
inline constexpr int kModuleParameterSlots = 8;
// Where a module parameter's gradient goes in a module's slots (learning).
inline int module_slot(ModuleParameter p, int axis) {
  return p == ModuleParameter::velocity ? axis : 2 + static_cast<int>(p);
}
// "velocity", "rate", ...: the text after a module's name.
const char* module_parameter_name(ModuleParameter p);

struct ParameterId {
  enum class Kind {
    viscosity,  // every spring's damping, N s/m
    friction,   // every node's Coulomb coefficient
    dt,         // the solver's step (the refresh interval when adaptive), s
    gravity,    // one axis, m/s^2
    input,      // a linguistic input of the scene's rule base
    module,     // a parameter of one of the scene's modules
  };
  Kind kind = Kind::viscosity;
  int axis = -1;   // 0, 1, 2 (x, y, z): gravity and module parameters; else -1
  int index = -1;  // input: into ParameterNames::inputs; module: into the scene's modules
  ModuleParameter parameter = ModuleParameter::velocity;  // module only

  static ParameterId of(Kind kind) { return {kind, -1, -1, ModuleParameter::velocity}; }
  static ParameterId gravity(int axis) {
    return {Kind::gravity, axis, -1, ModuleParameter::velocity};
  }
  static ParameterId input(int index) {
    return {Kind::input, -1, index, ModuleParameter::velocity};
  }
  static ParameterId module(int index, ModuleParameter p, int axis) {
    return {Kind::module, axis, index, p};
  }
};

bool operator==(const ParameterId& a, const ParameterId& b);
inline bool operator!=(const ParameterId& a, const ParameterId& b) {
  return !(a == b);
}

// What a scene's input and module ids index. Inputs are sorted by name: a rule
// base loaded into a running scene must take the same inputs, in whatever
// order it declares them, so an input id stays valid across it.
struct ParameterNames {
  std::vector<std::string> inputs;   // the linguistic material's inputs (none: numeric material)
  std::vector<std::string> modules;  // the modules' types, in the scene's order
};

// How text names module `index`: "wind" for the first module of its type,
// "wind[1]" for the second.
std::string module_name(const ParameterNames& names, int index);

// Every parameter the names allow, in the order a list of them is shown:
// viscosity, friction, dt, gravity.x|y|z, input.NAME..., then module parameters.
std::vector<ParameterId> all_parameters(const ParameterNames& names);

// "viscosity", "friction", "dt", "gravity.x", "input.mass", "wind.velocity.x"
// (the first wind module), "wind[1].velocity.x" (the second). Anything else,
// or a name the scene does not have, gives nullopt and, in `why`, a line that
// quotes the text and lists what the scene has.
std::optional<ParameterId> parse_parameter(const std::string& text, const ParameterNames& names,
                                           std::string* why = nullptr);
// The text parse_parameter reads back as `id`; an index the names do not
// have is written "input#7" or "module#7" (no scene has it: it parses to nothing).
std::string to_string(const ParameterId& id, const ParameterNames& names);

}  // namespace neurocloth
