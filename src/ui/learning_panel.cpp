// The Learning panel: a reference motion (a recording or markers) loaded and
// shown as ghost points beside the cloth, a fit to it started and stopped on
// its own worker thread while the cloth keeps running, its loss and each
// parameter plotted as it converges, and the result applied to the running
// cloth (the weights ramp to it). docs/viewer.md, "Learning panel".
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "ui/learning_session.h"
#include "ui/panels.h"

namespace neurocloth {

namespace {

const ImVec4 kError(1, 0.35f, 0.35f, 1);
const ImVec4 kGhostText(0.0f, 0.80f, 0.90f, 1);  // the ghosts' colour (render_palette.h)

void reference_section(PanelContext& ctx, LearningSession& s) {
  LearningSettings& set = s.settings();
  ImGui::SetNextItemWidth(280);
  ImGui::InputText("##reference", set.reference_path.data(), set.reference_path.size());
  ImGui::SameLine();
  ImGui::BeginDisabled(!ctx.status.scene);
  if (ImGui::Button("Load##reference")) {
    const std::string error = s.load_reference(set.reference_path.data(), *ctx.status.scene);
    if (!error.empty()) ctx.messages.error = error;
  }
  ImGui::EndDisabled();
  // What a frame sequence or a point cache does not say itself.
  ImGui::SetNextItemWidth(90);
  ImGui::InputFloat("frames/s", &set.reference_fps, 0, 0, "%.4g");
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("a PLY / XYZ frame sequence's or a PC2 cache's (0: the file's own)");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(90);
  ImGui::InputFloat("start, s", &set.reference_start, 0, 0, "%.4g");
  ImGui::SetNextItemWidth(220);
  ImGui::InputText("cache mesh (OBJ)", set.reference_mesh.data(), set.reference_mesh.size());
  if (!s.error().empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kError);
    ImGui::TextWrapped("%s", s.error().c_str());
    ImGui::PopStyleColor();
  }
  const auto& ref = s.reference();
  if (!ref) {
    ImGui::TextDisabled(
        "no reference: a recording (simulate --record), a markers or cloud CSV,\n"
        "a folder or %%04d pattern of PLY / XYZ frames, a PC2 / MDD cache");
    return;
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s: %s, %zu frames to %.3g s, %zu observed positions", ref->path.c_str(),
                     to_string(ref->source), ref->frames.size(),
                     ref->frames.empty() ? 0.0 : ref->frames.back().time, ref->observations());
  if (!ref->note.empty()) ImGui::TextWrapped("%s", ref->note.c_str());
  ImGui::PopStyleColor();
  ImGui::Checkbox("show as ghost points", &set.show_ghosts);
  if (s.ghost_count() > 0) {
    ImGui::SameLine();
    ImGui::TextColored(kGhostText, "%zu points", s.ghost_count());
    ImGui::TextWrapped("cloth to reference: RMS %.3g mm at t = %.3f s%s", 1e3 * s.ghost_rms_m(),
                       s.ghost_time(),
                       s.reference_ended() ? " (past its end: its last frame)" : "");
  }
}

void fit_settings(LearningSession& s, bool running) {
  LearningSettings& set = s.settings();
  ImGui::BeginDisabled(running);
  ImGui::InputText("parameters", set.params.data(), set.params.size());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "as fit --params: spring_constant, shear_constant, bend_constant, viscosity,\n"
        "node_mass, friction, module parameters (air_drag.rate, wind.drag, ...),\n"
        "or a material in words' inputs (input.mass, input.elasticity, ...)");
  if (s.reference() && s.reference()->is_cloud()) {
    ImGui::Checkbox("one-sided (a partial view)", &set.one_sided);
    const char* robust[] = {"squared", "Huber", "Cauchy"};
    ImGui::SetNextItemWidth(110);
    ImGui::Combo("distance", &set.robust, robust, 3);
    if (set.robust != 0) {
      ImGui::SameLine();
      ImGui::SetNextItemWidth(110);
      ImGui::SliderFloat("scale, m", &set.robust_scale, 1e-4f, 1.0f, "%.3g",
                         ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
    }
  }
  ImGui::Checkbox("online adaptation", &set.online);
  if (set.online) {
    ImGui::InputInt("window, steps", &set.window);
    set.window = std::max(1, set.window);
    ImGui::SliderFloat("learning rate", &set.learning_rate, 0.001f, 1.0f, "%.3g",
                       ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_AlwaysClamp);
  } else {
    const char* methods[] = {"L-BFGS", "gradient descent"};
    ImGui::Combo("optimizer", &set.optimizer, methods, 2);
    ImGui::InputInt("max iterations", &set.max_iterations);
    set.max_iterations = std::clamp(set.max_iterations, 1, 10000);
  }
  ImGui::EndDisabled();
  if (set.online) ImGui::Checkbox("apply each update to the cloth", &set.follow);
}

void fit_controls(PanelContext& ctx, LearningSession& s, bool running) {
  ImGui::BeginDisabled(running || !s.reference() || !ctx.status.scene);
  if (ImGui::Button("Start fit")) {
    const std::string why = s.start_fit(ctx.status.scene);
    if (!why.empty()) ctx.messages.error = why;
  }
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!running);
  if (ImGui::Button("Stop")) s.stop_fit();
  ImGui::EndDisabled();
  ImGui::SameLine();
  ImGui::BeginDisabled(!s.progress().outcome);
  if (ImGui::Button("Apply to cloth")) {
    const std::string why = s.apply(ctx.post);
    if (!why.empty()) ctx.messages.error = why;
  }
  ImGui::EndDisabled();
}

// A history as a line plot, the newest value in its overlay.
void plot(const char* id, const std::vector<double>& history, bool log10, const char* format,
          double shown) {
  std::vector<float> v;
  v.reserve(history.size());
  for (const double x : history)
    v.push_back(static_cast<float>(log10 ? std::log10(std::max(x, 1e-300)) : x));
  char overlay[64];
  std::snprintf(overlay, sizeof overlay, format, shown);
  ImGui::PlotLines(id, v.data(), static_cast<int>(v.size()), 0, overlay, FLT_MAX, FLT_MAX,
                   ImVec2(ImGui::GetContentRegionAvail().x, 50));
}

void progress_section(const FitProgress& p) {
  if (p.state == FitProgress::State::idle) return;
  if (p.state == FitProgress::State::running) {
    if (p.online)
      ImGui::Text("adapting: t = %.3g of %.3g s, window %d", p.online_time, p.duration,
                  p.iteration);
    else
      ImGui::Text("fitting: iteration %d", p.iteration);
  } else if (p.state == FitProgress::State::failed) {
    ImGui::PushStyleColor(ImGuiCol_Text, kError);
    ImGui::TextWrapped("fit failed: %s", p.message.c_str());
    ImGui::PopStyleColor();
  } else {
    ImGui::TextWrapped("%s%s", p.reason ? (std::string(to_string(*p.reason)) + ": ").c_str() : "",
                       p.message.c_str());
  }
  if (p.loss.empty()) return;
  plot("##loss", p.loss, true, "log10 loss; now %.3g m^2", p.loss.back());
  ImGui::TextDisabled("%s, RMS %.3g mm", p.online ? "window loss per update" : "loss per iteration",
                      1e3 * p.rms_m.back());
  for (std::size_t c = 0; c < p.names.size() && c < p.values.size(); ++c) {
    if (p.values[c].empty()) continue;
    ImGui::PushID(static_cast<int>(c));
    plot("##value", p.values[c], false, "%.5g", p.values[c].back());
    ImGui::PopID();
    ImGui::TextDisabled("%s, %s", p.names[c].c_str(), p.units[c].c_str());
  }
}

}  // namespace

void learning_panel(PanelContext& ctx) {
  if (!ctx.learning) return;
  LearningSession& s = *ctx.learning;
  const bool running = s.fit_running();
  reference_section(ctx, s);
  ImGui::Separator();
  fit_settings(s, running);
  fit_controls(ctx, s, running);
  progress_section(s.progress());
  if (!s.applied().empty()) ImGui::TextWrapped("applied: %s", s.applied().c_str());
}

}  // namespace neurocloth
