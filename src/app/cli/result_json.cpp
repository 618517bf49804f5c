#include "app/cli/result_json.h"

#include <cmath>
#include <cstdio>

#include "core/scene/cantilever.h"
#include "tradeoff/drape_shape.h"

namespace neurocloth {

nlohmann::json state_json(const ClothState& s, const NodeNumbering& numbering, bool velocities) {
  nlohmann::json a = nlohmann::json::array();
  for (std::size_t k = 0; k < s.size(); ++k) {
    const auto i = static_cast<std::size_t>(numbering.node(static_cast<int>(k)));
    const Vec3 v = velocities ? s.velocity(i) : s.position(i);
    a.push_back({v.x(), v.y(), v.z()});
  }
  return a;
}

nlohmann::json energy_json(const Energy& e) {
  return {{"kinetic", e.kinetic},
          {"potential", e.potential()},
          {"total", e.total()},
          {"spring", e.spring},
          {"gravity", e.gravity}};
}

std::vector<FabricTestReading> fabric_test_readings(const Scene& scene, const ClothState& state) {
  std::vector<FabricTestReading> out;
  const std::shared_ptr<const DrapeMeter> meter = scene_drape_meter(scene);
  if (meter && meter->node_count() == state.size()) {
    const DrapeShape d = meter->measure(state);
    out.push_back({"drape",
                   {{"coefficient", d.coefficient},
                    {"nodes", d.folds},
                    {"support", to_string(meter->support().shape)}},
                   describe(d, meter->support())});
  }
  if (const auto setup = cantilever_setup(scene)) {
    const CantileverReading r = read_cantilever(*setup, state);
    constexpr double kDegree = 3.141592653589793 / 180;
    char line[200];
    std::snprintf(line, sizeof line,
                  "cantilever: chord %.2f degrees at an overhang of %.4g mm: bending length %.4g "
                  "mm (Peirce's formula %.4g), bending rigidity %.4g N m",
                  r.chord_angle / kDegree, 1e3 * setup->overhang, 1e3 * r.bending_length,
                  1e3 * r.peirce_length, r.bending_rigidity);
    // A strip that has not dropped has no bending length: null, not NaN.
    auto number = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); };
    out.push_back({"cantilever",
                   {{"chord_angle", number(r.chord_angle / kDegree)},
                    {"overhang", setup->overhang},
                    {"bending_length", number(r.bending_length)},
                    {"peirce_length", number(r.peirce_length)},
                    {"bending_rigidity", number(r.bending_rigidity)}},
                   line});
  }
  return out;
}

nlohmann::json simulation_result(const Simulation& sim, const NodeNumbering& numbering,
                                 const std::string& scene_path, double wall_seconds) {
  const SolverSettings& s = sim.settings();
  nlohmann::json doc;
  doc["status"] = to_string(sim.status());
  if (sim.status() != RunStatus::ok) doc["reason"] = sim.divergence_reason();
  doc["scene"] = scene_path;
  doc["integrator"] = to_string(s.integrator);
  doc["precision"] = to_string(s.precision);
  doc["damping"] = to_string(s.damping);
  doc["step_bound"] = to_string(s.step_bound);
  doc["adaptive"] = s.adaptive;
  doc["safety"] = s.adaptive_settings.safety;
  doc["dt"] = s.dt;
  doc["time"] = sim.time();
  doc["steps"] = sim.steps();
  doc["rejected_steps"] = sim.rejected_steps();
  doc["force_evaluations"] = sim.force_evaluations();
  doc["cg_iterations"] = sim.cg_iterations();
  doc["wall_seconds"] = wall_seconds;
  doc["nodes"] = sim.network().node_count();
  doc["springs"] = sim.network().spring_count();
  doc["energy"] = energy_json(sim.energy());
  // The modules the scene declared, in the order the step runs them, and what
  // each cost: the rest of wall_seconds is the network itself.
  nlohmann::json modules = nlohmann::json::array();
  double module_seconds = 0;
  for (const ModuleReport& m : sim.module_reports()) {
    modules.push_back(
        {{"type", m.type},
         {"seconds", m.seconds},
         {"calls", m.calls},
         {"state_bytes", m.state_bytes},
         {"declaration", m.declaration.empty()
                             ? nlohmann::json()
                             : nlohmann::json::parse(m.declaration, nullptr, false)}});
    module_seconds += m.seconds;
  }
  doc["modules"] = modules;
  doc["module_seconds"] = module_seconds;
  doc["positions"] = state_json(sim.state(), numbering, false);
  doc["velocities"] = state_json(sim.state(), numbering, true);
  return doc;
}

}  // namespace neurocloth
