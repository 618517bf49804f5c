// The Scene panel: which scene runs, loading another, adding an OBJ as an
// obstacle, reset / pause / step, the drape test's figures over a support, and
// the scene's active modules with the keys they were declared with.
#include <imgui.h>

#include <array>
#include <string>

#include "ui/panels.h"
#include "ui/ui_requests.h"

namespace neurocloth {

namespace {

void load(PanelContext& ctx, const std::string& path) {
  const std::string error = request_scene(path, ctx.post);
  if (!error.empty()) ctx.messages.error = error;
}

// An OBJ as an obstacle: added to the scene as loaded, which starts over with it.
void add_obstacle(PanelContext& ctx) {
  UiValues& v = ctx.values;
  ImGui::SetNextItemWidth(250);  // the button beside it is wider than Load
  ImGui::InputTextWithHint("##obstacle", "obstacle OBJ file", v.obstacle_path.data(),
                           v.obstacle_path.size());
  ImGui::SameLine();
  ImGui::BeginDisabled(!ctx.status.scene);
  if (ImGui::Button("Add obstacle")) {
    const std::array<float, 3>& t = v.obstacle_translate;
    const std::string error = request_obstacle(*ctx.status.scene, ctx.scene, v.obstacle_path.data(),
                                               v.obstacle_scale, Vec3(t[0], t[1], t[2]), ctx.post);
    if (!error.empty()) ctx.messages.error = "Add obstacle: " + error;
  }
  ImGui::EndDisabled();
  ImGui::SetNextItemWidth(80);
  ImGui::InputFloat("scale", &v.obstacle_scale, 0, 0, "%.4g");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(200);
  ImGui::InputFloat3("at (m)", v.obstacle_translate.data(), "%.3g");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("where the OBJ's origin goes (metres, Y up); the scene restarts with it");
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
  if (ctx.scene.drape().active()) {
    const std::string& drape = ctx.scene.drape().line(ctx.snapshot, ImGui::GetTime());
    if (!drape.empty()) {
      ImGui::TextUnformatted(drape.c_str());
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip(
            "ISO 9073-9's drape coefficient (the cloth's shadow outside its support over the "
            "flat cloth's) and its nodes (folds); docs/tradeoff.md");
    }
  }
  ImGui::SetNextItemWidth(280);
  ImGui::InputText("##scene", ctx.values.scene_path.data(), ctx.values.scene_path.size());
  ImGui::SameLine();
  if (ImGui::Button("Load")) load(ctx, ctx.values.scene_path.data());
  add_obstacle(ctx);
  run_controls(ctx);
  ImGui::TextDisabled("commands: %ld applied, %ld refused", s.commands_applied, s.commands_refused);
  if (ImGui::TreeNodeEx("Modules", ImGuiTreeNodeFlags_DefaultOpen)) {
    modules(s);
    ImGui::TreePop();
  }
}

}  // namespace neurocloth
