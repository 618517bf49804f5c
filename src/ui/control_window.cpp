// The control window: one ImGui window docked to the left edge, errors first
// (they must be seen), then the panels as collapsing sections.
#include <imgui.h>

#include "ui/learning_session.h"
#include "ui/panels.h"

namespace neurocloth {

namespace {

const ImVec4 kErrorColour(1, 0.35f, 0.35f, 1);

void error_lines(PanelContext& ctx) {
  if (!ctx.messages.error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("%s", ctx.messages.error.c_str());
    ImGui::PopStyleColor();
    if (ImGui::SmallButton("dismiss")) ctx.messages.error.clear();
  }
  if (!ctx.status.last_error.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("simulation: %s", ctx.status.last_error.c_str());
    ImGui::PopStyleColor();
  }
}

}  // namespace

void draw_controls(PanelContext& ctx) {
  const ImGuiIO& io = ImGui::GetIO();
  ImGui::SetNextWindowPos(ImVec2(0, 0));
  ImGui::SetNextWindowSize(ImVec2(kControlWidth, io.DisplaySize.y));
  ImGui::Begin("neurocloth", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
  // Widgets leave room for their labels.
  ImGui::PushItemWidth(-150);
  error_lines(ctx);
  if (ImGui::CollapsingHeader("Scene", ImGuiTreeNodeFlags_DefaultOpen)) scene_panel(ctx);
  if (ImGui::CollapsingHeader("Solver", ImGuiTreeNodeFlags_DefaultOpen)) solver_panel(ctx);
  if (ImGui::CollapsingHeader("Material", ImGuiTreeNodeFlags_DefaultOpen)) material_panel(ctx);
  if (ImGui::CollapsingHeader("Forces")) forces_panel(ctx);
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) view_panel(ctx);
  if (ctx.learning) {
    // Opens by itself the first time a reference is loaded.
    if (ctx.learning->reference()) ImGui::SetNextItemOpen(true, ImGuiCond_Once);
    if (ImGui::CollapsingHeader("Learning")) learning_panel(ctx);
  }
  ImGui::Text("%.0f fps", io.Framerate);
  ImGui::PopItemWidth();
  ImGui::End();
}

}  // namespace neurocloth
