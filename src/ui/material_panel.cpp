// The Material panel: a linguistic material's inputs as sliders, each with its
// membership functions plotted and the value marked; every rule's firing
// strength; the parameters that result; presets and loading a rule base.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "core/scene/fuzzy_material.h"
#include "ui/membership_plot.h"
#include "ui/panels.h"
#include "ui/parameter_input.h"

namespace neurocloth {

namespace {

constexpr float kPlotHeight = 48;

bool load_rules(PanelContext& ctx, const std::string& path) {
  const std::string error = request_rules(ctx.scene, path, ctx.post);
  if (!error.empty()) ctx.messages.error = error;
  return error.empty();
}

// The same file under two spellings ("scenes/../materials/cloth.fcl").
bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  return std::filesystem::weakly_canonical(a, ec) == std::filesystem::weakly_canonical(b, ec);
}

// Loads the preset's rule base if it is not the one in use, then sets every input.
void apply_preset(PanelContext& ctx, const std::string& name) {
  try {
    const LinguisticMaterial preset = load_preset(name);
    if (!same_file(preset.rules_path, ctx.scene.fuzzy()->rules_path()) &&
        !load_rules(ctx, preset.rules_path))
      return;
    for (const auto& [input, value] : preset.inputs) {
      const std::string refusal =
          request_parameter(ctx.scene, ctx.values, ctx.post, "input." + input, value);
      if (!refusal.empty()) ctx.messages.error = "preset " + name + ": " + refusal;
    }
  } catch (const std::exception& e) {
    ctx.messages.error = e.what();
  }
}

void presets_and_rules(PanelContext& ctx) {
  static const std::vector<std::string> presets = preset_names();
  const char* current = presets.empty() ? "(none)" : presets[ctx.values.preset].c_str();
  ImGui::SetNextItemWidth(160);
  if (ImGui::BeginCombo("##preset", current)) {
    for (std::size_t i = 0; i < presets.size(); ++i)
      if (ImGui::Selectable(presets[i].c_str(), ctx.values.preset == static_cast<int>(i)))
        ctx.values.preset = static_cast<int>(i);
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  if (ImGui::Button("Apply preset") && !presets.empty())
    apply_preset(ctx, presets[ctx.values.preset]);

  ImGui::SetNextItemWidth(260);
  ImGui::InputText("##rules", ctx.values.rules_path.data(), ctx.values.rules_path.size());
  ImGui::SameLine();
  if (ImGui::Button("Load FCL")) load_rules(ctx, ctx.values.rules_path.data());
}

void inputs(PanelContext& ctx, FuzzyView& view) {
  const fuzzy::FuzzySystem& system = view.system();
  const std::vector<std::string>& names = ctx.scene.names().inputs;
  for (const fuzzy::LinguisticVariable& v : system.inputs) {
    const auto known = std::find(names.begin(), names.end(), v.name);
    const ParameterId id = ParameterId::input(static_cast<int>(known - names.begin()));
    double* value = known == names.end() ? nullptr : ctx.values.field(id, ctx.scene.names());
    ImGui::PushID(v.name.c_str());
    if (value) {
      parameter_slider(ctx, v.name.c_str(), id);
      membership_plot(v, *value, ImVec2(ImGui::GetContentRegionAvail().x, kPlotHeight));
    } else {
      ImGui::TextDisabled("%s: not an input of the running material", v.name.c_str());
    }
    ImGui::PopID();
  }
}

void rules(FuzzyView& view, const DerivedMaterial& derived) {
  const fuzzy::FuzzySystem& system = view.system();
  for (std::size_t b = 0; b < system.blocks.size(); ++b) {
    const fuzzy::RuleBlock& block = system.blocks[b];
    ImGui::TextDisabled("RULEBLOCK %s", block.name.c_str());
    for (std::size_t r = 0; r < block.rules.size(); ++r) {
      const fuzzy::Rule& rule = block.rules[r];
      const double strength = derived.report.activation[b][r];
      char bar[16];
      std::snprintf(bar, sizeof bar, "%.2f", strength);
      ImGui::ProgressBar(static_cast<float>(strength), ImVec2(48, 0), bar);
      ImGui::SameLine();
      std::string then;
      for (const fuzzy::Consequent& c : rule.consequents)
        then += (then.empty() ? "" : ", ") + view.describe(c);
      ImGui::TextWrapped("%s: IF %s THEN %s", rule.label.c_str(),
                         view.describe(rule.condition).c_str(), then.c_str());
    }
  }
}

void outputs(FuzzyView& view, const DerivedMaterial& derived) {
  const fuzzy::FuzzySystem& system = view.system();
  for (std::size_t i = 0; i < system.outputs.size(); ++i) {
    const fuzzy::LinguisticVariable& v = system.outputs[i];
    ImGui::Text("%s = %.4g", v.name.c_str(), derived.report.outputs[i]);
    ImGui::PushID(static_cast<int>(i));
    membership_plot(v, derived.report.outputs[i],
                    ImVec2(ImGui::GetContentRegionAvail().x, kPlotHeight));
    ImGui::PopID();
  }
  for (const std::string& note : derived.report.notes)
    ImGui::TextColored(ImVec4(1, 0.8f, 0.3f, 1), "%s", note.c_str());
}

void numeric_material(PanelContext& ctx) {
  const Material& m = ctx.scene.material();
  ImGui::TextWrapped(
      "Given as numbers. Presets and rule bases need a linguistic material "
      "(\"material\": {\"rules\", \"inputs\"}), e.g. scenes/hanging_fuzzy.json.");
  ImGui::Text("spring constant %.4g N/m (shear %.4g, bend %.4g)", m.spring_constant, m.shear(),
              m.bend());
  ImGui::Text("node mass %.4g kg", m.node_mass);
  ImGui::Text("viscosity %.4g N s/m, friction %.3g (Solver panel)", ctx.status.viscosity,
              ctx.status.friction);
}

}  // namespace

void material_panel(PanelContext& ctx) {
  if (!ctx.scene.fuzzy()) {
    numeric_material(ctx);
    return;
  }
  ImGui::TextDisabled("rules: %s", ctx.scene.fuzzy()->rules_path().c_str());
  presets_and_rules(ctx);  // may replace the rule base: take the view only after it
  FuzzyView& view = *ctx.scene.fuzzy();
  inputs(ctx, view);
  const DerivedMaterial& derived = view.evaluate(ctx.values.inputs);
  if (ImGui::TreeNodeEx("Rules (firing strength)", ImGuiTreeNodeFlags_DefaultOpen)) {
    rules(view, derived);
    ImGui::TreePop();
  }
  if (ImGui::TreeNodeEx("Resulting parameters", ImGuiTreeNodeFlags_DefaultOpen)) {
    outputs(view, derived);
    ImGui::TreePop();
  }
}

}  // namespace neurocloth
