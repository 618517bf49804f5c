// The View panel: what the renderer draws, the camera, screenshots, and a
// reminder of the mouse and keys (docs/viewer.md has the full list).
#include <imgui.h>

#include <string>

#include "ui/panels.h"

namespace neurocloth {

namespace {
const double kDragGainMin = 100, kDragGainMax = 20000;
}  // namespace

void view_panel(PanelContext& ctx) {
  RenderOptions& r = ctx.render;
  ImGui::Checkbox("wireframe", &r.wireframe);
  ImGui::SameLine();
  ImGui::Checkbox("springs", &r.springs);
  ImGui::SameLine();
  ImGui::Checkbox("nodes", &r.nodes);
  ImGui::Checkbox("strain map", &r.strain);
  if (r.strain) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(120);
    ImGui::SliderFloat("red at", &r.strain_max, 0.01f, 0.5f, "%.2f");
  }
  ImGui::Checkbox("grid", &r.grid);
  ImGui::SameLine();
  ImGui::Checkbox("colliders", &r.colliders);
  ImGui::SameLine();
  ImGui::Checkbox("forces", &r.forces);
  const SceneGeometry* g = ctx.snapshot.geometry.get();
  if (g && !g->coarse_triangles.empty() && g->triangles.size() > kWindowClothTriangles) {
    // A fine grid is drawn on every other row and column unless asked.
    bool every = r.max_cloth_triangles == 0;
    if (ImGui::Checkbox("every triangle (slower)", &every))
      r.max_cloth_triangles = every ? 0 : kWindowClothTriangles;
  }

  double gain = ctx.values.drag_gain;
  if (ImGui::SliderScalar("drag strength, 1/s^2", ImGuiDataType_Double, &gain, &kDragGainMin,
                          &kDragGainMax, "%.0f", ImGuiSliderFlags_Logarithmic)) {
    // A ctrl+click typed value is not clamped by ImGui: refuse it out of range.
    if (gain >= kDragGainMin && gain <= kDragGainMax)
      ctx.values.drag_gain = gain;
    else
      ctx.messages.error = "drag strength " + std::to_string(gain) + " refused: valid range " +
                           std::to_string(int(kDragGainMin)) + " .. " +
                           std::to_string(int(kDragGainMax)) + " 1/s^2";
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the dragged node is pulled with m x this x distance (capped at 0.5 m)");

  if (ImGui::Button("Frame cloth (F)")) ctx.requests.frame_camera = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset camera (R)")) ctx.requests.reset_camera = true;
  ImGui::SameLine();
  if (ImGui::Button("Screenshot (F12)")) ctx.requests.screenshot = true;
  if (!ctx.messages.screenshot.empty())
    ImGui::TextWrapped("saved %s", ctx.messages.screenshot.c_str());
  ImGui::TextDisabled(
      "left-drag a node: pull it; right-click: pin/unpin\n"
      "right- or alt+left-drag: orbit; middle-drag: pan; wheel: zoom");
}

}  // namespace neurocloth
