#pragma once
// The paper's fuzzy system in use: a rule base whose outputs are the network's
// physical parameters (spring_constant, node_mass, viscosity, friction, and
// optionally shear_constant and bend_constant) and a set of linguistic inputs
// ("mass", "elasticity", "force") that select them.
#include <map>
#include <string>
#include <vector>

#include "core/fuzzy/fuzzy_system.h"
#include "core/fuzzy/inference.h"
#include "core/network/material.h"

namespace neurocloth {

// A material described in words: a rule base and values for its inputs, as a
// scene's material block or a preset file (assets/materials/NAME.json) gives them.
struct LinguisticMaterial {
  std::string rules_path;  // resolved
  std::map<std::string, double> inputs;
  std::string source;        // the file the inputs came from, for messages
  std::string inputs_field;  // where in it ("material.inputs" or "inputs")
};

// Throws InputError when there is no such preset or it is malformed.
LinguisticMaterial load_preset(const std::string& name);
// The names of the shipped presets, sorted.
std::vector<std::string> preset_names();

struct DerivedMaterial {
  Material material;
  fuzzy::InferenceReport report;  // rule activations, clamped inputs, defaulted outputs
};

// How a derived material moves with each input: the material and, per input
// (in the rule base's order), the derivative of each constant the network
// takes. shear_constant and bend_constant hold the derivatives of shear() and
// bend() (what the shear and bend springs get), so they are never "follow the
// spring constant" markers here.
struct MaterialSensitivity {
  DerivedMaterial derived;
  std::vector<Material> d_inputs;
};

class FuzzyMaterial {
 public:
  // The outputs every material rule base must define.
  static constexpr const char* kOutputs[] = {"spring_constant", "node_mass", "viscosity",
                                             "friction"};
  // Outputs a rule base may define; without them shear and bend springs take
  // the spring constant (Material::shear(), Material::bend()).
  static constexpr const char* kOptionalOutputs[] = {"shear_constant", "bend_constant"};
  // node_mass is the mass of this much cloth (a node of a 5 cm grid), m^2;
  // scenes give each node its lumped share (Scene::build_network).
  static constexpr double kReferenceNodeArea = neurocloth::kReferenceNodeArea;

  // Throws InputError (naming `source`) when an output is missing or its range
  // admits values the network cannot take (node_mass <= 0, negative constants).
  FuzzyMaterial(fuzzy::FuzzySystem system, std::string source);
  // A .fcl or .fis rule base (fuzzy/rule_file.h).
  static FuzzyMaterial load(const std::string& path);

  // Every input of the rule base must be given, and nothing else; `where` names
  // the place they came from in messages (e.g. "scene.json" / "material.inputs").
  DerivedMaterial derive(const std::map<std::string, double>& inputs, const std::string& where = "",
                         const std::string& field = "inputs") const;

  // derive() with the exact derivatives of the material (fuzzy::infer_gradient).
  MaterialSensitivity sensitivity(const std::map<std::string, double>& inputs,
                                  const std::string& where = "",
                                  const std::string& field = "inputs") const;

  const fuzzy::FuzzySystem& system() const { return system_; }
  const std::string& source() const { return source_; }

 private:
  std::vector<double> input_vector(const std::map<std::string, double>& inputs,
                                   const std::string& where, const std::string& field) const;
  // The material the outputs y give (inference values or their derivatives).
  Material material_from(const std::vector<double>& y) const;

  fuzzy::FuzzySystem system_;
  std::string source_;
  // Index of each of kOutputs then kOptionalOutputs in the system (-1: absent).
  int outputs_[6];
};

}  // namespace neurocloth
