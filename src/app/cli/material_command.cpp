// `neurocloth-cli material`: what a rule base makes of linguistic inputs —
// every output, every rule's activation, and anything clamped or defaulted.
#include <cmath>
#include <cstdio>
#include <map>

#include <nlohmann/json.hpp>

#include "app/cli/commands.h"
#include "core/fuzzy/formats/rule_file.h"
#include "core/fuzzy/inference.h"
#include "core/io/input_error.h"
#include "core/scene/fuzzy_material.h"

namespace neurocloth {
namespace {

std::map<std::string, double> parse_assignments(const std::vector<std::string>& items) {
  std::map<std::string, double> values;
  for (const std::string& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("command line", "--input", "expected NAME=VALUE, got '" + item + "'");
    const std::string name = item.substr(0, eq), text = item.substr(eq + 1);
    std::size_t used = 0;
    double v = 0;
    try {
      v = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != text.size() || text.empty() || !std::isfinite(v))
      throw InputError("command line", "--input " + name, "'" + text + "' is not a finite number");
    if (values.count(name)) throw InputError("command line", "--input " + name, "given twice");
    values[name] = v;
  }
  return values;
}

}  // namespace

int run_material(const MaterialOptions& o) {
  LinguisticMaterial lm;
  if (o.preset) {
    lm = load_preset(*o.preset);
  } else {
    lm.rules_path = o.rules;
    lm.inputs = parse_assignments(o.inputs);
    lm.source = "command line";
    lm.inputs_field = "--input";
  }
  const fuzzy::FuzzySystem system = fuzzy::read_rule_file(lm.rules_path);
  std::vector<double> x;
  std::string names;
  for (const auto& v : system.inputs)
    names += (names.empty() ? "" : ", ") + v.name;
  for (const auto& [name, value] : lm.inputs)
    if (system.input_index(name) < 0)
      throw InputError(lm.source, lm.inputs_field + " " + name,
                       "the rule base has no input '" + name + "' (its inputs: " + names + ")");
  for (const auto& v : system.inputs) {
    const auto it = lm.inputs.find(v.name);
    if (it == lm.inputs.end())
      throw InputError(lm.source, lm.inputs_field + " " + v.name,
                       "missing (the rule base needs: " + names + ")");
    x.push_back(it->second);
  }
  const fuzzy::InferenceReport r = fuzzy::infer(system, x);

  if (o.json) {
    nlohmann::json doc;
    doc["rules"] = lm.rules_path;
    if (o.preset) doc["preset"] = *o.preset;
    for (std::size_t i = 0; i < x.size(); ++i)
      doc["inputs"][system.inputs[i].name] = x[i];
    for (std::size_t k = 0; k < r.outputs.size(); ++k) {
      doc["outputs"][system.outputs[k].name] = r.outputs[k];
      if (r.defaulted[k]) doc["defaulted"].push_back(system.outputs[k].name);
    }
    for (std::size_t i = 0; i < x.size(); ++i)
      if (r.clamped[i]) doc["clamped"].push_back(system.inputs[i].name);
    doc["rule_activations"] = nlohmann::json::array();
    for (std::size_t b = 0; b < system.blocks.size(); ++b)
      for (std::size_t k = 0; k < system.blocks[b].rules.size(); ++k)
        doc["rule_activations"].push_back({{"block", system.blocks[b].name},
                                           {"rule", system.blocks[b].rules[k].label},
                                           {"activation", r.activation[b][k]}});
    doc["notes"] = r.notes;
    std::printf("%s\n", doc.dump(1).c_str());
    return kExitOk;
  }
  std::printf("%s%s:", lm.rules_path.c_str(),
              o.preset ? (" (preset " + *o.preset + ")").c_str() : "");
  for (std::size_t i = 0; i < x.size(); ++i)
    std::printf(" %s = %g", system.inputs[i].name.c_str(), x[i]);
  std::printf("\noutputs:\n");
  for (std::size_t k = 0; k < r.outputs.size(); ++k)
    std::printf("  %-18s %.6g%s\n", system.outputs[k].name.c_str(), r.outputs[k],
                r.defaulted[k] ? "  (default: no rule fired)" : "");
  std::printf("rule activations:\n");
  for (std::size_t b = 0; b < system.blocks.size(); ++b)
    for (std::size_t k = 0; k < system.blocks[b].rules.size(); ++k)
      std::printf("  %s / RULE %-4s %.4f\n", system.blocks[b].name.c_str(),
                  system.blocks[b].rules[k].label.c_str(), r.activation[b][k]);
  for (const auto& note : r.notes)
    std::printf("note: %s\n", note.c_str());
  return kExitOk;
}

}  // namespace neurocloth
