// The Forces panel: gravity, the wind (scenes with a wind module) and the
// force the mouse drag applies right now.
#include <imgui.h>

#include <algorithm>
#include <string>

#include "ui/panels.h"
#include "ui/parameter_input.h"

namespace neurocloth {

void forces_panel(PanelContext& ctx) {
  const char* const axes[] = {"x", "y", "z"};
  ImGui::TextDisabled("gravity, m/s^2");
  for (int k = 0; k < 3; ++k)
    parameter_field(ctx, (std::string("gravity ") + axes[k]).c_str(), ParameterId::gravity(k));
  const auto& modules = ctx.scene.names().modules;
  const auto wind = std::find(modules.begin(), modules.end(), "wind");
  if (ctx.values.has_wind && wind != modules.end()) {
    ImGui::TextDisabled("wind, m/s");
    const int index = static_cast<int>(wind - modules.begin());
    for (int k = 0; k < 3; ++k)
      parameter_field(ctx, (std::string("wind ") + axes[k]).c_str(),
                      ParameterId::module(index, ModuleParameter::velocity, k));
  } else {
    ImGui::TextDisabled("no wind module in this scene");
  }
  for (const FrameSnapshot::AppliedForce& f : ctx.snapshot.forces)
    ImGui::Text("drag on node %d: %.3g N", ctx.snapshot.geometry->numbering.source(f.node),
                f.force.norm());
}

}  // namespace neurocloth
