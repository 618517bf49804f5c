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
#include "core/io/json_fields.h"
#include "core/scene/fuzzy_material.h"
#include "core/scene/grid_builder.h"
#include "core/scene/measured_material.h"

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

// --measured: a fabric's name, or KEY=VALUE pairs read as a scene's
// material.measured would be (the same keys, limits and messages).
MeasuredPreset measured_from(const std::vector<std::string>& items) {
  if (items.size() == 1 && items[0].find('=') == std::string::npos)
    return load_measured_preset(items[0]);
  MeasuredPreset p;
  p.name = "command line";
  nlohmann::json v = nlohmann::json::object();
  for (const auto& [name, value] : parse_assignments(items))
    v[name] = value;
  const JsonFields in(v.dump(), "command line");
  p.measured = read_measured_material(in, in.root(), "--measured");
  return p;
}

constexpr double kGfCm2PerCm = 9.80665e-5;  // N m in one gf cm^2/cm (KES-FB2's unit)
constexpr double kGravity = 9.80665;

int run_measured(const MaterialOptions& o) {
  if (!(o.spacing > 0) || !limits::kSpacing.contains(o.spacing))
    throw InputError("command line", "--spacing", limits::kSpacing.refusal(o.spacing));
  const MeasuredPreset p = measured_from(o.measured);
  const MeasuredMaterial& m = p.measured;
  // A square grid with structural and shear springs (what the weights are
  // for), and the same cloth as a mesh of equilateral-ish triangles.
  GridSpec g;
  g.rows = g.cols = 3;
  g.spacing = o.spacing;
  g.families = SpringFamilies{true, true, false};
  const ClothTopology grid = build_grid(g);
  std::vector<std::string> notes;
  const Material mat = measured_constants(m, grid, &notes);
  const double node_mass = m.areal_density * o.spacing * o.spacing;  // an interior node's
  const double sheet = grid_tensile_stiffness(mat);
  nlohmann::json doc;
  doc["fabric"] = p.name;
  if (!p.path.empty()) doc["file"] = p.path;
  doc["measured"] = {{"areal_density", m.areal_density},
                     {"tensile_stiffness", m.tensile_stiffness},
                     {"shear_stiffness", m.shear()},
                     {"damping", m.damping},
                     {"friction", m.friction}};
  doc["grid"] = {{"spacing", o.spacing},          {"spring_constant", mat.spring_constant},
                 {"shear_constant", mat.shear()}, {"viscosity", mat.viscosity},
                 {"node_mass", node_mass},        {"sheet_tensile_stiffness", sheet}};
  doc["mesh"] = {{"edge_stiffness", "tensile_stiffness * (A1 + A2) / |e|^2"},
                 {"shear_stiffness", 0.375 * m.tensile_stiffness}};
  if (m.bending_rigidity) {
    const double b = *m.bending_rigidity;
    doc["measured"]["bending_rigidity"] = b;
    doc["bending"] = {{"rigidity", b},
                      {"rigidity_kes", b / kGfCm2PerCm},
                      {"bending_length", std::cbrt(b / (m.areal_density * kGravity))}};
  }
  for (const auto& [key, source] : p.sources)
    doc["sources"][key] = source;
  if (o.json) {
    std::printf("%s\n", doc.dump(1).c_str());
    return kExitOk;
  }
  std::printf("%s%s\n", p.name.c_str(), p.path.empty() ? "" : (" (" + p.path + ")").c_str());
  std::printf(
      "measured: areal density %g kg/m^2, tensile %g N/m, shear %g N/m, damping %g N s/m, "
      "friction %g\n",
      m.areal_density, m.tensile_stiffness, m.shear(), m.damping, m.friction);
  std::printf("on a grid of %g m (structural and shear springs, no bend springs):\n", o.spacing);
  std::printf("  spring_constant  %.6g N/m   (the sheet's tensile stiffness: %.6g N/m)\n",
              mat.spring_constant, sheet);
  std::printf("  shear_constant   %.6g N/m\n", mat.shear());
  std::printf("  viscosity        %.6g N s/m\n", mat.viscosity);
  std::printf("  node_mass        %.6g kg (an interior node; each carries its share of area)\n",
              node_mass);
  std::printf(
      "on a triangle mesh: each edge %g N/m times (A1 + A2) / |e|^2; shear follows as %g "
      "N/m\n",
      m.tensile_stiffness, 0.375 * m.tensile_stiffness);
  if (m.bending_rigidity) {
    const double b = *m.bending_rigidity;
    std::printf("bending module: rigidity %.6g N m (%.4g gf cm^2/cm), bending length %.4g mm\n", b,
                b / kGfCm2PerCm, 1e3 * std::cbrt(b / (m.areal_density * kGravity)));
  } else {
    std::printf("no bending_rigidity: the cloth does not resist bending\n");
  }
  for (const auto& [key, source] : p.sources)
    std::printf("source of %s: %s\n", key.c_str(), source.c_str());
  return kExitOk;
}

}  // namespace

int run_material(const MaterialOptions& o) {
  if (!o.measured.empty()) return run_measured(o);
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
