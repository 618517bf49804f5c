// The Scene panel: which scene runs, loading another, reset / pause / step,
// and the scene's active modules with the keys they were declared with.
#include <imgui.h>

#include "ui/panels.h"
#include "ui/ui_requests.h"

namespace neurocloth {

namespace {

void load(PanelContext& ctx, const std::string& path) {
  const std::string error = request_scene(path, ctx.post);
  if (!error.empty()) ctx.messages.error = error;
}

void run_controls(PanelContext& ctx) {
  const bool paused = ctx.status.paused;
  if (ImGui::Button("Reset")) ctx.post(Reset{});
  ImGui::SameLine();
  if (ImGui::Button(paused ? "Resume (Space)" : "Pause (Space)")) ctx.post(SetPaused{!paused});
  ImGui::SameLine();
  ImGui::BeginDisabled(!paused);
  if (ImGui::Button("Step (N)")) ctx.post(SingleStep{});
  ImGui::EndDisabled();
}

void modules(const SimulationStatus& s) {
  if (s.modules.empty()) {
    ImGui::TextDisabled("no modules");
    return;
  }
  for (const ModuleReport& m : s.modules) {
    ImGui::BulletText("%s", m.type.c_str());
    ImGui::Indent();
    ImGui::TextWrapped("%s", m.declaration.c_str());
    ImGui::TextDisabled("%ld calls, %.3f s", m.calls, m.seconds);
    ImGui::Unindent();
  }
}

}  // namespace

void scene_panel(PanelContext& ctx) {
  const SimulationStatus& s = ctx.status;
  ImGui::Text("%s", s.scene_name.c_str());
  ImGui::TextDisabled("%s", s.scene_path.c_str());
  ImGui::TextWrapped("%s", ctx.scene.cloth_summary().c_str());
  ImGui::SetNextItemWidth(280);
  ImGui::InputText("##scene", ctx.values.scene_path.data(), ctx.values.scene_path.size());
  ImGui::SameLine();
  if (ImGui::Button("Load")) load(ctx, ctx.values.scene_path.data());
  run_controls(ctx);
  ImGui::TextDisabled("commands: %ld applied, %ld refused", s.commands_applied, s.commands_refused);
  if (ImGui::TreeNodeEx("Modules", ImGuiTreeNodeFlags_DefaultOpen)) {
    modules(s);
    ImGui::TreePop();
  }
}

}  // namespace neurocloth
