#include "fuzzy_material.h"

#include <cmath>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "asset_paths.h"
#include "fuzzy/rule_file.h"
#include "input_error.h"
#include "linguistic_material_json.h"
#include "text_file.h"

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
  const std::string path = assets_directory() + "/materials/" + name + ".json";
  std::error_code ec;
  if (name.empty() || name.find('/') != std::string::npos ||
      !std::filesystem::is_regular_file(path, ec)) {
    std::string known;
    for (const auto& n : preset_names())
      known += (known.empty() ? "" : ", ") + n;
    throw InputError(path, "", "no material preset '" + name + "' (presets: " + known + ")");
  }
  const JsonFields in(read_text_file(path, "material preset", kMaxSceneBytes), path);
  return read_linguistic_material(in, in.root(), "");
}

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(assets_directory() + "/materials", ec))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

FuzzyMaterial::FuzzyMaterial(fuzzy::FuzzySystem system, std::string source)
    : system_(std::move(system)), source_(std::move(source)) {
  for (int k = 0; k < 4; ++k) {
    outputs_[k] = system_.output_index(kOutputs[k]);
    if (outputs_[k] < 0)
      throw InputError(
          source_, "VAR_OUTPUT",
          std::string("a material rule base needs an output named '") + kOutputs[k] + "'");
    const fuzzy::LinguisticVariable& v = system_.outputs[outputs_[k]];
    const bool mass = k == 1;
    if (mass ? !(v.min > 0) : v.min < 0)
      throw InputError(
          source_, std::string("DEFUZZIFY ") + kOutputs[k],
          mass ? "RANGE must be above 0 (a node needs mass)" : "RANGE must not go below 0");
  }
}

FuzzyMaterial FuzzyMaterial::load(const std::string& path) {
  return FuzzyMaterial(fuzzy::read_rule_file(path), path);
}

DerivedMaterial FuzzyMaterial::derive(const std::map<std::string, double>& inputs,
                                      const std::string& where, const std::string& field) const {
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

  DerivedMaterial d;
  d.report = fuzzy::infer(system_, x);
  const auto& y = d.report.outputs;
  d.material.spring_constant = y[outputs_[0]];
  d.material.node_mass = y[outputs_[1]];
  d.material.viscosity = y[outputs_[2]];
  d.material.friction = y[outputs_[3]];
  return d;
}

}  // namespace neurocloth
