#include "core/scene/fuzzy_material.h"

#include <cmath>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <sstream>

#include "core/fuzzy/formats/rule_file.h"
#include "core/io/asset_paths.h"
#include "core/io/input_error.h"
#include "core/io/text_file.h"
#include "core/scene/linguistic_material_json.h"

namespace neurocloth {

LinguisticMaterial read_linguistic_material(const JsonFields& in, const nlohmann::json& m,
                                            const std::string& field) {
  const auto name = [&](const std::string& key) { return JsonLocator::member(field, key); };
  in.allow_only(m, field, {"rules", "inputs", "description"});
  LinguisticMaterial lm;
  lm.source = in.file();
  lm.inputs_field = name("inputs");
  lm.rules_path = resolve_path(in.file(), in.string(in.member(m, field, "rules"), name("rules")));
  const nlohmann::json& inputs = in.member(m, field, "inputs");
  in.require_object(inputs, lm.inputs_field);
  for (const auto& item : inputs.items())
    lm.inputs[item.key()] =
        in.number(item.value(), JsonLocator::member(lm.inputs_field, item.key()));
  return lm;
}

LinguisticMaterial load_preset(const std::string& name) {
  const std::string path =
      named_json_file(assets_directory() + "/materials", name, "material preset", "presets");
  const JsonFields in(read_text_file(path, "material preset", kMaxSceneBytes), path);
  return read_linguistic_material(in, in.root(), "");
}

std::vector<std::string> preset_names() {
  return json_names_in(assets_directory() + "/materials");
}

namespace {

// The one table from a rule base's outputs to the material: slot k is
// kOutputs[k], then kOptionalOutputs[k - kRequired]; outputs_[k] holds where the
// rule base has it.
struct OutputSlot {
  double Material::*field;
  bool positive;  // must be above 0 (a node needs mass), else only not below 0
};
constexpr OutputSlot kSlots[6] = {
    {&Material::spring_constant, false}, {&Material::node_mass, true},
    {&Material::viscosity, false},       {&Material::friction, false},
    {&Material::shear_constant, false},  {&Material::bend_constant, false}};
constexpr int kSlotCount = static_cast<int>(std::size(kSlots));
constexpr int kShearSlot = 4, kBendSlot = 5;
constexpr int kRequired = static_cast<int>(std::size(FuzzyMaterial::kOutputs));
static_assert(std::size(kSlots) ==
                  std::size(FuzzyMaterial::kOutputs) + std::size(FuzzyMaterial::kOptionalOutputs),
              "one slot per output, required then optional");

const char* output_name(int k) {
  return k < kRequired ? FuzzyMaterial::kOutputs[k]
                       : FuzzyMaterial::kOptionalOutputs[k - kRequired];
}

}  // namespace

FuzzyMaterial::FuzzyMaterial(fuzzy::FuzzySystem system, std::string source)
    : system_(std::move(system)), source_(std::move(source)) {
  for (int k = 0; k < kSlotCount; ++k) {
    outputs_[k] = system_.output_index(output_name(k));
    if (outputs_[k] < 0) {
      if (k >= kRequired) continue;
      throw InputError(
          source_, "VAR_OUTPUT",
          std::string("a material rule base needs an output named '") + output_name(k) + "'");
    }
    const fuzzy::LinguisticVariable& v = system_.outputs[outputs_[k]];
    if (kSlots[k].positive ? !(v.min > 0) : v.min < 0)
      throw InputError(source_, std::string("DEFUZZIFY ") + output_name(k),
                       kSlots[k].positive ? "RANGE must be above 0 (a node needs mass)"
                                          : "RANGE must not go below 0");
  }
}

FuzzyMaterial FuzzyMaterial::load(const std::string& path) {
  return FuzzyMaterial(fuzzy::read_rule_file(path), path);
}

std::vector<double> FuzzyMaterial::input_vector(const std::map<std::string, double>& inputs,
                                                const std::string& where,
                                                const std::string& field) const {
  const std::string file = where.empty() ? source_ : where;
  std::vector<double> x(system_.inputs.size());
  for (const auto& [name, value] : inputs) {
    const int i = system_.input_index(name);
    std::string names;
    for (const auto& v : system_.inputs)
      names += (names.empty() ? "" : ", ") + v.name;
    if (i < 0)
      throw InputError(
          file, field + "." + name,
          "the rule base " + source_ + " has no input '" + name + "' (its inputs: " + names + ")");
    if (!std::isfinite(value))
      throw InputError(file, field + "." + name, "must be a finite number");
    x[i] = value;
  }
  for (const auto& v : system_.inputs)
    if (!inputs.count(v.name))
      throw InputError(file, field + "." + v.name, "missing: the rule base needs every input");
  return x;
}

Material FuzzyMaterial::material_from(const std::vector<double>& y) const {
  Material m;
  for (int k = 0; k < kSlotCount; ++k)
    if (outputs_[k] >= 0) m.*kSlots[k].field = y[static_cast<std::size_t>(outputs_[k])];
  return m;
}

DerivedMaterial FuzzyMaterial::derive(const std::map<std::string, double>& inputs,
                                      const std::string& where, const std::string& field) const {
  DerivedMaterial d;
  d.report = fuzzy::infer(system_, input_vector(inputs, where, field));
  d.material = material_from(d.report.outputs);
  return d;
}

MaterialSensitivity FuzzyMaterial::sensitivity(const std::map<std::string, double>& inputs,
                                               const std::string& where,
                                               const std::string& field) const {
  // Seeded with the inputs only: the material's parameters are not asked for.
  fuzzy::InferenceGradient g =
      fuzzy::infer_gradient(system_, input_vector(inputs, where, field), {});
  MaterialSensitivity s;
  s.derived.report = std::move(g.report);
  s.derived.material = material_from(s.derived.report.outputs);
  for (Eigen::Index j = 0; j < g.d_inputs.cols(); ++j) {
    std::vector<double> dy(static_cast<std::size_t>(g.d_inputs.rows()));
    for (Eigen::Index o = 0; o < g.d_inputs.rows(); ++o)
      dy[static_cast<std::size_t>(o)] = g.d_inputs(o, j);
    Material d = material_from(dy);
    // Without their own outputs, shear and bend springs follow the spring constant.
    if (outputs_[kShearSlot] < 0) d.shear_constant = d.spring_constant;
    if (outputs_[kBendSlot] < 0) d.bend_constant = d.spring_constant;
    s.d_inputs.push_back(d);
  }
  return s;
}

}  // namespace neurocloth
