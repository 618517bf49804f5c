#include "learn/fit/fitted_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "chart/loss_chart.h"
#include "core/io/json_writer.h"
#include "core/io/text_file.h"
#include "core/scene/element_weights.h"
#include "core/scene/fuzzy_material.h"
#include "core/scene/measured_material.h"

namespace neurocloth {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

nlohmann::ordered_json vec3_json(const Vec3& v) {
  return nlohmann::ordered_json::array({v.x(), v.y(), v.z()});
}

nlohmann::ordered_json material_json(const Material& m) {
  nlohmann::ordered_json out = {{"spring_constant", m.spring_constant},
                                {"node_mass", m.node_mass},
                                {"viscosity", m.viscosity},
                                {"friction", m.friction}};
  if (m.shear_constant >= 0) out["shear_constant"] = m.shear_constant;
  if (m.bend_constant >= 0) out["bend_constant"] = m.bend_constant;
  return out;
}

// A collider's contact: the friction keys, when the fit moved them.
void patch_contact(nlohmann::ordered_json& out, const ContactSpec& was, const ContactSpec& now) {
  if (now.friction && now.friction != was.friction) out["friction"] = *now.friction;
  if (now.static_friction && now.static_friction != was.static_friction)
    out["static_friction"] = *now.static_friction;
}

// Writes into the module's JSON object the values a fit can change that differ
// from what the file said; everything else stays as written.
void patch_module(nlohmann::ordered_json& out, const ModuleSpec& was, const ModuleSpec& now) {
  if (was.index() != now.index())
    throw std::logic_error("fitted_scene_json: a fitted module changed type");
  std::visit(
      [&](const auto& n) {
        using T = std::decay_t<decltype(n)>;
        const T& w = std::get<T>(was);
        if constexpr (std::is_same_v<T, AirDragSpec>) {
          if (n.rate != w.rate) out["rate"] = n.rate;
        } else if constexpr (std::is_same_v<T, BendingSpec>) {
          if (n.rigidity != w.rigidity) out["rigidity"] = *n.rigidity;
        } else if constexpr (std::is_same_v<T, WindSpec>) {
          if (n.velocity != w.velocity) out["velocity"] = vec3_json(n.velocity);
          if (n.density != w.density) out["density"] = n.density;
          if (n.drag != w.drag) out["drag"] = n.drag;
          if (n.lift != w.lift) out["lift"] = n.lift;
          if (n.skin != w.skin) out["skin"] = n.skin;
        } else if constexpr (std::is_same_v<T, PlaneSpec> || std::is_same_v<T, BoxSpec> ||
                             std::is_same_v<T, SphereSpec> || std::is_same_v<T, CapsuleSpec> ||
                             std::is_same_v<T, CylinderSpec> || std::is_same_v<T, MeshSpec>) {
          patch_contact(out, w.contact, n.contact);
        } else if constexpr (std::is_same_v<T, PinMotionSpec>) {
          if (n.keyframes != w.keyframes) {  // a fitted path: every key, as the reader reads them
            nlohmann::ordered_json keys = nlohmann::ordered_json::array();
            for (const auto& [t, offset] : n.keyframes)
              keys.push_back({{"t", t}, {"offset", vec3_json(offset)}});
            out["keyframes"] = keys;
          }
        }
      },
      now);
}

// The scene as FITTED.json's loader will build it: its material (numbers, or
// words when the inputs were fitted) without side-file weights.
ClothNetwork network_from_material(const FittedModel& model) {
  Scene s = model.scene;
  s.element_weights.reset();
  return s.build_network();
}

bool same_weights(const ClothNetwork& a, const ClothNetwork& b) {
  return a.springs.stiffness == b.springs.stiffness && a.springs.damping == b.springs.damping &&
         a.springs.rest_length == b.springs.rest_length &&
         a.masses.inverse_mass == b.masses.inverse_mass;
}

json parameter_json(const ParameterUncertainty& p) {
  json out = {{"name", p.name}, {"value", p.value}};
  if (std::isfinite(p.sd)) {
    out["sd"] = p.sd;
    if (std::isfinite(p.relative_sd)) out["relative_sd"] = p.relative_sd;
    out["verdict"] = to_string(p.verdict);
  }
  return out;
}

std::string csv_number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace

ClothNetwork FittedModel::network() const {
  ClothNetwork net = scene.build_network();
  if (!weights.stiffness.empty()) net.springs.stiffness = weights.stiffness;
  if (!weights.damping.empty()) net.springs.damping = weights.damping;
  if (!weights.inverse_mass.empty()) net.masses.inverse_mass = weights.inverse_mass;
  if (!weights.friction.empty()) net.masses.friction = weights.friction;
  if (!rest_lengths.empty()) net.springs.rest_length = rest_lengths;
  return net;
}

FittedFiles fitted_file_names(const std::string& out) {
  fs::path base(out);
  base.replace_extension();
  const std::string b = base.string();
  return {out, b + ".weights.json", b + ".loss.csv", b + ".loss.png", b + ".example.csv"};
}

std::string rebased_path(const std::string& from, const std::string& written,
                         const std::string& to) {
  if (fs::path(written).is_absolute()) return written;
  const fs::path target = fs::absolute(resolve_path(from, written)).lexically_normal();
  const fs::path folder = fs::absolute(to).parent_path().lexically_normal();
  const fs::path relative = target.lexically_relative(folder);
  std::error_code ec;
  if (!relative.empty() && fs::equivalent(resolve_path(to, relative.string()), target, ec) && !ec)
    return relative.string();
  return target.string();
}

std::optional<json> fitted_weights_json(const FittedModel& model) {
  const ClothNetwork fitted = model.network();
  if (same_weights(fitted, network_from_material(model))) return std::nullopt;
  return element_weights_json(fitted, model.scene.topology);
}

nlohmann::ordered_json fitted_scene_json(const Scene& original, const FittedModel& model,
                                         const FitSummary& summary, const std::string& out,
                                         const std::string& weights_file) {
  nlohmann::ordered_json doc =
      nlohmann::ordered_json::parse(read_text_file(original.path, "scene file", kMaxSceneBytes));
  const json was_material = json::parse(doc["material"].dump());
  if (const auto& words = model.scene.fuzzy_material) {
    nlohmann::ordered_json inputs;
    for (const auto& [name, value] : words->inputs)
      inputs[name] = value;
    doc["material"] = {{"rules", rebased_path("", words->rules_path, out)}, {"inputs", inputs}};
  } else if (original.measured_material) {
    // As written: a fit changes no lab value but the rigidity of the bending
    // the material implies (below); family constants are not fitted for it.
  } else {
    doc["material"] = material_json(model.scene.material);
  }
  if (model.scene.initial_velocity != original.initial_velocity)
    doc["cloth"]["initial_velocity"] = vec3_json(model.scene.initial_velocity);
  if (doc.contains("cloth") && doc["cloth"].contains("mesh")) {
    nlohmann::ordered_json& obj = doc["cloth"]["mesh"]["obj"];
    obj = rebased_path(original.path, obj.get<std::string>(), out);
  }
  // A measured bending_rigidity with no bending module in the file implies one,
  // the scene's last: its fitted rigidity goes back into the material.
  const std::size_t written = doc.contains("modules") ? doc["modules"].size() : 0;
  if (model.scene.modules.size() != original.modules.size() ||
      original.modules.size() - written > 1)
    throw std::logic_error("fitted_scene_json: the fitted scene's modules are not the file's");
  if (original.modules.size() == written + 1) {
    const auto& now = std::get<BendingSpec>(model.scene.modules.back().spec);
    const auto& was = std::get<BendingSpec>(original.modules.back().spec);
    if (now.rigidity != was.rigidity) {
      MeasuredMaterial m = *original.measured_material;
      m.bending_rigidity = now.rigidity;
      doc["material"] = {
          {"measured", nlohmann::ordered_json::parse(measured_material_json(m).dump())}};
    }
  }
  if (doc.contains("modules")) {
    nlohmann::ordered_json& modules = doc["modules"];
    for (std::size_t i = 0; i < modules.size(); ++i)
      patch_module(modules[i], original.modules[i].spec, model.scene.modules[i].spec);
  }
  if (weights_file.empty())
    doc.erase("element_weights");
  else
    doc["element_weights"] = weights_file;

  json note = {{"source_scene", original.path},
               {"reference", summary.reference},
               {"optimizer", summary.optimizer},
               {"stop", summary.stop_reason},
               {"stop_message", summary.stop_message},
               {"iterations", summary.iterations},
               {"loss", summary.loss},
               {"rms_m", summary.rms_m},
               {"uncertainty", summary.uncertainty}};
  if (original.fuzzy_material)
    note["replaces"] = "the material in words (" + original.fuzzy_material->rules_path +
                       "): " + was_material.dump();
  else
    note["replaces"] = was_material;
  if (!summary.words.empty()) note["in_words"] = summary.words;
  json params = json::array();
  for (const ParameterUncertainty& p : summary.parameters)
    params.push_back(parameter_json(p));
  note["parameters"] = std::move(params);
  doc["fitted"] = nlohmann::ordered_json::parse(note.dump());
  return doc;
}

std::string loss_csv(const FitHistory& h) {
  std::string text = "iteration,loss,rms_mm,seconds";
  for (const std::string& c : h.columns)
    text += "," + c;
  text += "\n";
  for (const FitHistoryRow& r : h.rows) {
    if (r.parameters.size() != h.columns.size())
      throw std::logic_error("loss_csv: one value per column");
    text += std::to_string(r.iteration) + "," + csv_number(r.loss) + "," +
            csv_number(r.rms_m * 1e3) + "," + csv_number(r.seconds);
    for (double v : r.parameters)
      text += "," + csv_number(v);
    text += "\n";
  }
  return text;
}

std::optional<std::string> tuning_example(const Scene& original, const FitSummary& summary) {
  if (!original.fuzzy_material || !summary.words.empty()) return std::nullopt;
  std::string header, row;
  const fuzzy::FuzzySystem& rules = original.fuzzy_material->rules->system();
  for (const auto& [name, value] : original.fuzzy_material->inputs) {
    // The value the rule base saw: a scene's input outside its RANGE is
    // clamped, and tune-rules refuses one outside it.
    double seen = value;
    if (const int i = rules.input_index(name); i >= 0) {
      const fuzzy::LinguisticVariable& v = rules.inputs[static_cast<std::size_t>(i)];
      seen = std::min(std::max(value, v.min), v.max);
    }
    header += (header.empty() ? "" : ",") + name;
    row += (row.empty() ? "" : ",") + csv_number(seen);
  }
  bool any = false;
  for (const char* output : FuzzyMaterial::kOutputs)
    for (const ParameterUncertainty& p : summary.parameters)
      if (p.name == output) {
        header += std::string(",") + output;
        row += "," + csv_number(p.value);
        any = true;
      }
  if (!any) return std::nullopt;
  return "# from a fit of " + original.path + " to " + summary.reference + "\n" + header + "\n" +
         row + "\n";
}

FittedFiles write_fit_outputs(const Scene& original, const FittedModel& model,
                              const FitSummary& summary, const FitHistory& history,
                              const std::string& out) {
  FittedFiles files = fitted_file_names(out);
  // Everything in memory first: a failure here writes nothing.
  const std::optional<json> weights = fitted_weights_json(model);
  if (!weights) files.weights.clear();
  const nlohmann::ordered_json scene = fitted_scene_json(
      original, model, summary, out, weights ? fs::path(files.weights).filename().string() : "");
  const json scene_check = json::parse(scene.dump());
  for (const json* doc : {&scene_check, weights ? &*weights : nullptr}) {
    if (!doc) continue;
    if (const auto at = first_non_finite(*doc))
      throw std::runtime_error(out + ": the fitted value at " + *at + " is not finite");
  }
  const std::string csv = loss_csv(history);
  const std::optional<std::string> example = tuning_example(original, summary);
  if (!example) files.example.clear();
  std::vector<LossPoint> curve;
  for (const FitHistoryRow& r : history.rows)
    curve.push_back({r.iteration, r.loss});
  std::ostringstream png;
  LogLogChart(loss_chart_spec(curve, "Fit of " + original.name + " to " +
                                         fs::path(summary.reference).filename().string()))
      .write_png(png, files.png);

  // The scene last: it names the others.
  std::vector<std::string> written;
  try {
    if (weights) {
      write_file_atomically(files.weights, weights->dump(1) + "\n");
      written.push_back(files.weights);
    }
    write_file_atomically(files.csv, csv);
    written.push_back(files.csv);
    write_file_atomically(files.png, png.str());
    written.push_back(files.png);
    if (example) {
      write_file_atomically(files.example, *example);
      written.push_back(files.example);
    }
    write_file_atomically(files.scene, scene.dump(2) + "\n");
  } catch (...) {
    for (const std::string& f : written) {
      std::error_code ignored;
      fs::remove(f, ignored);
    }
    throw;
  }
  return files;
}

}  // namespace neurocloth
