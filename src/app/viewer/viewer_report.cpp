#include "app/viewer/viewer_report.h"

#include <stdexcept>

#include "core/io/json_writer.h"
#include "ui/ui_values.h"

namespace neurocloth {

namespace {

using nlohmann::json;

json vec(const Vec3& v) {
  return json::array({v.x(), v.y(), v.z()});
}

// Where `node` is in `snapshot`, and when.
json place(int node, const FrameSnapshot& snapshot) {
  json at = {{"time", snapshot.time}, {"serial", snapshot.serial}};
  if (node >= 0 && static_cast<std::size_t>(node) < snapshot.geometry->node_count)
    at["position"] = vec(snapshot.node(node));
  return at;
}

// The index the user knows `node` by: its vertex in the scene's mesh file
// (a grid's nodes are already in that order). -1 (missed the cloth) stays.
int shown(int node, const FrameSnapshot& snapshot) {
  return node >= 0 ? snapshot.geometry->numbering.source(node) : node;
}

json status_json(const SimulationStatus& s) {
  json inputs = json::object();
  for (const auto& [name, value] : s.material_inputs)
    inputs[name] = value;
  json modules = json::array();
  for (const ModuleReport& m : s.modules)
    modules.push_back({{"type", m.type}, {"declaration", m.declaration}});
  json out = {{"scene_name", s.scene_name},
              {"scene_path", s.scene_path},
              {"run", to_string(s.run)},
              {"time", s.time},
              {"steps", s.steps},
              {"rejected_steps", s.rejected_steps},
              {"step_cap", s.step_cap},
              {"steps_per_second", s.steps_per_second},
              {"realtime_ratio", s.realtime_ratio},
              {"keeping_up", s.keeping_up},
              {"paused", s.paused},
              {"commands_applied", s.commands_applied},
              {"commands_refused", s.commands_refused},
              {"last_error", s.last_error},
              {"integrator", to_string(s.integrator)},
              {"adaptive", s.adaptive},
              {"dt", s.dt},
              {"viscosity", s.viscosity},
              {"friction", s.friction},
              {"gravity", vec(s.gravity)},
              {"material_inputs", inputs},
              {"modules", modules}};
  if (s.wind) out["wind"] = vec(*s.wind);
  return out;
}

}  // namespace

void ViewerReport::picked(int node, double x, double y, const FrameSnapshot& snapshot) {
  picks_.push_back({{"node", shown(node, snapshot)}, {"pixel", {x, y}}, {"time", snapshot.time}});
  if (node >= 0)
    drags_.push_back({{"node", shown(node, snapshot)}, {"press", place(node, snapshot)}});
}

void ViewerReport::released(int node, const Vec3& target, const FrameSnapshot& snapshot) {
  if (!drags_.empty() && drags_.back()["node"] == shown(node, snapshot)) {
    drags_.back()["release"] = place(node, snapshot);
    drags_.back()["target"] = vec(target);
  }
}

void ViewerReport::pinned(int node, bool pinned, const FrameSnapshot& snapshot) {
  pins_.push_back(
      {{"node", shown(node, snapshot)}, {"pinned", pinned}, {"at", place(node, snapshot)}});
}

void ViewerReport::parameter(double t, const std::string& name, double value,
                             const std::string& refusal) {
  json set = {{"t", t}, {"name", name}, {"value", value}, {"accepted", refusal.empty()}};
  if (!refusal.empty()) set["refusal"] = refusal;
  sets_.push_back(set);
}

void ViewerReport::probe(double t, int vertex, const FrameSnapshot& snapshot) {
  const bool exists =
      vertex >= 0 && static_cast<std::size_t>(vertex) < snapshot.geometry->node_count;
  const int node = exists ? snapshot.geometry->numbering.node(vertex) : -1;
  json p = place(node, snapshot);
  p["t"] = t;
  p["node"] = vertex;
  if (node >= 0 && static_cast<std::size_t>(node) < snapshot.pinned.size())
    p["pinned"] = snapshot.pinned[node] != 0;
  probes_.push_back(p);
}

void ViewerReport::screenshot(const std::string& path, int width, int height) {
  screenshots_.push_back({{"path", path}, {"width", width}, {"height", height}});
}

void ViewerReport::error(double t, const std::string& message) {
  errors_.push_back({{"t", t}, {"message", message}});
}

void ViewerReport::learning(const LearningSession& s) {
  json out;
  if (const auto& ref = s.reference())
    out["reference"] = {{"path", ref->path},
                        {"source", to_string(ref->source)},
                        {"frames", ref->frames.size()},
                        {"observations", ref->observations()}};
  else
    out["reference"] = nullptr;
  out["ghosts"] = {{"count", s.ghost_count()},
                   {"time", s.ghost_time()},
                   {"rms_m", s.ghost_rms_m()},
                   {"reference_ended", s.reference_ended()}};
  const FitProgress& p = s.progress();
  json values = json::object();
  for (std::size_t c = 0; c < p.names.size() && c < p.values.size(); ++c)
    if (!p.values[c].empty()) values[p.names[c]] = p.values[c].back();
  out["fit"] = {{"state", to_string(p.state)},
                {"online", p.online},
                {"rows", p.loss.size()},
                {"iteration", p.iteration},
                {"loss", p.loss},
                {"values", values},
                {"message", p.message},
                {"reason", p.reason ? to_string(*p.reason) : ""}};
  out["applied"] = {{"count", s.applied_count()}, {"last", s.applied()}};
  out["error"] = s.error();
  learning_ = out;
}

void ViewerReport::write(const std::string& path, const SimulationStatus& status,
                         const FrameStats& stats, const ParameterNames& names) const {
  json sets = sets_;
  // What the simulation shows for each parameter asked for, at the end.
  for (json& set : sets)
    if (const auto id = parse_parameter(set["name"].get<std::string>(), names))
      if (const auto v = status_value(status, *id, names)) set["status_value"] = *v;
  const json report = {{"picks", picks_},
                       {"drags", drags_},
                       {"pins", pins_},
                       {"sets", sets},
                       {"probes", probes_},
                       {"screenshots", screenshots_},
                       {"errors", errors_},
                       {"learning", learning_},
                       {"frames",
                        {{"drawn", stats.frames()},
                         {"skipped", stats.skipped_frames()},
                         {"median_fps", stats.median_fps()}}},
                       {"simulation",
                        {{"median_steps_per_second", stats.median_steps_per_second()},
                         {"median_realtime_ratio", stats.median_realtime_ratio()}}},
                       {"status", status_json(status)}};
  write_json_atomically(path, report);
}

}  // namespace neurocloth
