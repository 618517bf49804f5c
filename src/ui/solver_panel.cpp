// The Solver panel: how the network is propagated (integrator, step, adaptive,
// damping, friction) and how it is doing (t_c, rejections, speed, energy).
#include <imgui.h>

#include <iterator>
#include <optional>
#include <vector>

#include "ui/panels.h"
#include "ui/parameter_input.h"
#include "ui/ui_requests.h"

namespace neurocloth {

namespace {

void settings(PanelContext& ctx) {
  UiValues& v = ctx.values;
  const char* current = to_string(kAllIntegrators[v.integrator]);
  if (ImGui::BeginCombo("integrator", current)) {
    for (std::size_t i = 0; i < std::size(kAllIntegrators); ++i)
      if (ImGui::Selectable(to_string(kAllIntegrators[i]), v.integrator == static_cast<int>(i))) {
        v.integrator = static_cast<int>(i);
        ctx.post(SetIntegrator{kAllIntegrators[i]});
      }
    ImGui::EndCombo();
  }
  if (ImGui::Checkbox("adaptive (paper, Table 1)", &v.adaptive)) ctx.post(SetAdaptive{v.adaptive});
  using Kind = ParameterId::Kind;
  parameter_field(ctx, v.adaptive ? "refresh interval, s" : "time step, s",
                  ParameterId::of(Kind::dt));
  parameter_field(ctx, "damping (viscosity), N s/m", ParameterId::of(Kind::viscosity));
  parameter_field(ctx, "friction", ParameterId::of(Kind::friction));
}

// Instead of a step by hand: the cheapest measured setting within an accuracy.
void accuracy(PanelContext& ctx) {
  const AccuracyTrade& trade = ctx.scene.trade();
  if (!trade.table) {
    ImGui::TextDisabled("accuracy: %s", trade.note.c_str());
    return;
  }
  UiValues& v = ctx.values;
  float percent = 100 * v.accuracy;
  const float lo = static_cast<float>(100 * trade.finest),
              hi = static_cast<float>(100 * trade.loosest);
  ImGui::SliderFloat("accuracy, % of size", &percent, lo, hi, "%.3g %%",
                     ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp |
                         ImGuiSliderFlags_NoRoundToFormat);
  v.accuracy = percent / 100;
  if (ImGui::IsItemDeactivatedAfterEdit()) {
    const std::string refusal = request_accuracy(ctx.scene, v, ctx.post, v.accuracy);
    if (!refusal.empty()) {
      ctx.messages.error = refusal;
      v.accuracy_pick.clear();
    }
  }
  if (!v.accuracy_pick.empty()) ImGui::TextWrapped("picked %s", v.accuracy_pick.c_str());
}

// The window chose another solver to keep a resized cloth in real time.
void realtime_pick(PanelContext& ctx) {
  std::optional<RealtimePick>& pick = ctx.scene.realtime_pick;
  if (!pick || !pick->switched) return;
  ImGui::TextWrapped("%s", pick->note.c_str());
  if (ImGui::Button("use the scene's own solver")) {
    const SolverSettings& own = pick->own;
    ctx.post(
        solver_command(own));  // its iterations and tolerance too: the pick may have changed them
    UiValues& v = ctx.values;
    for (std::size_t i = 0; i < std::size(kAllIntegrators); ++i)
      if (kAllIntegrators[i] == own.integrator) v.integrator = static_cast<int>(i);
    v.adaptive = own.adaptive;
    v.dt = own.dt;
    pick.reset();
  }
}

void progress(const SimulationStatus& s) {
  ImGui::Text("t = %.3f s, %ld steps (%ld rejected)", s.time, s.steps, s.rejected_steps);
  ImGui::Text("t_c = %.3g s, %.0f steps/s", s.step_cap, s.steps_per_second);
  if (!s.keeping_up)
    ImGui::TextColored(ImVec4(1, 0.7f, 0.2f, 1), "not keeping up: %.2fx real time",
                       s.realtime_ratio);
  if (!s.stability_notice.empty())
    ImGui::TextColored(ImVec4(1, 0.7f, 0.2f, 1), "%s", s.stability_notice.c_str());
  if (s.run == RunStatus::diverged)
    ImGui::TextColored(ImVec4(1, 0.3f, 0.3f, 1), "diverged: %s", s.divergence_reason.c_str());
}

void energy_plot(const SimulationStatus& s) {
  if (s.energy_history.empty()) return;
  std::vector<float> e(s.energy_history.begin(), s.energy_history.end());
  char label[48];
  std::snprintf(label, sizeof label, "%.4g J", s.energy_history.back());
  ImGui::PlotLines("##energy", e.data(), static_cast<int>(e.size()), 0, label, FLT_MAX, FLT_MAX,
                   ImVec2(ImGui::GetContentRegionAvail().x, 60));
  ImGui::TextDisabled("total energy, recent samples");
}

}  // namespace

void solver_panel(PanelContext& ctx) {
  realtime_pick(ctx);
  settings(ctx);
  accuracy(ctx);
  ImGui::Separator();
  progress(ctx.status);
  energy_plot(ctx.status);
}

}  // namespace neurocloth
