#include "ui/parameter_input.h"

#include <imgui.h>

namespace neurocloth {

namespace {

void range_tooltip(const ParameterRange* range) {
  if (range && ImGui::IsItemHovered())
    ImGui::SetTooltip("%s: %s", range->name.c_str(), range_text(*range).c_str());
}

}  // namespace

void parameter_field(PanelContext& ctx, const char* label, const ParameterId& id) {
  double* shown = ctx.values.field(id, ctx.scene.names());
  if (!shown) return;
  // Edit a copy: the UI value changes only when the simulation is asked to follow.
  double typed = *shown;
  if (ImGui::InputDouble(label, &typed, 0, 0, "%.6g", ImGuiInputTextFlags_EnterReturnsTrue) &&
      typed != *shown) {
    const std::string refusal = request_parameter(ctx.scene, ctx.values, ctx.post, id, typed);
    if (!refusal.empty()) ctx.messages.error = refusal;
  }
  range_tooltip(ctx.scene.range(id));
}

void parameter_slider(PanelContext& ctx, const char* label, const ParameterId& id) {
  double* shown = ctx.values.field(id, ctx.scene.names());
  const ParameterRange* range = ctx.scene.range(id);
  if (!shown) return;
  if (!range) {
    parameter_field(ctx, label, id);  // the refusal will say why
    return;
  }
  double dragged = *shown;
  // No AlwaysClamp: a ctrl+click typed value out of range is refused, not clamped silently.
  if (ImGui::SliderScalar(label, ImGuiDataType_Double, &dragged, &range->min, &range->max,
                          "%.3g") &&
      dragged != *shown) {
    const std::string refusal = request_parameter(ctx.scene, ctx.values, ctx.post, id, dragged);
    if (!refusal.empty()) ctx.messages.error = refusal;
  }
  range_tooltip(range);
}

}  // namespace neurocloth
