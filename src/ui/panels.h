#pragma once
// The panels of the control window, one file each. Each draws its widgets
// for one frame: it reads ctx.status / ctx.snapshot, edits ctx.values and
// posts commands. None of them touches the simulation.
#include "ui/panel_context.h"

namespace neurocloth {

// The whole control window: error lines on top, then every panel.
void draw_controls(PanelContext& ctx);

void material_panel(PanelContext& ctx);  // linguistic inputs, memberships, rules, presets
void solver_panel(PanelContext& ctx);    // integrator, step, damping, speed, energy
void scene_panel(PanelContext& ctx);     // load, reset, pause, step, modules
void forces_panel(PanelContext& ctx);    // gravity, wind, the drag
void view_panel(PanelContext& ctx);      // render toggles, camera, screenshot, mouse help
void learning_panel(PanelContext& ctx);  // reference, ghosts, fit, loss and parameters, apply

// Width of the control window, px: the 3D view keeps the rest of the window.
inline constexpr float kControlWidth = 400;

}  // namespace neurocloth
