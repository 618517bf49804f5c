// The Forces panel: gravity, the wind (scenes with a wind module) and the
// force the mouse drag applies right now.
#include <imgui.h>

#include "panels.h"
#include "parameter_input.h"

namespace neurocloth {

void forces_panel(PanelContext& ctx) {
  ImGui::TextDisabled("gravity, m/s^2");
  parameter_field(ctx, "gravity x", "gravity.x");
  parameter_field(ctx, "gravity y", "gravity.y");
  parameter_field(ctx, "gravity z", "gravity.z");
  if (ctx.values.has_wind) {
    ImGui::TextDisabled("wind, m/s");
    parameter_field(ctx, "wind x", "wind.x");
    parameter_field(ctx, "wind y", "wind.y");
    parameter_field(ctx, "wind z", "wind.z");
  } else {
    ImGui::TextDisabled("no wind module in this scene");
  }
  for (const FrameSnapshot::AppliedForce& f : ctx.snapshot.forces)
    ImGui::Text("drag on node %d: %.3g N", f.node, f.force.norm());
}

}  // namespace neurocloth
