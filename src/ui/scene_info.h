#pragma once
// The UI's own copy of the running scene: what the panels need that the status
// does not carry (valid parameter ranges, node masses for the drag force, the
// rule base to plot). Built on the UI thread from a Scene value; the simulation
// thread has its own copy and is never asked.
#include <optional>
#include <string>
#include <vector>

#include "core/scene/scene.h"
#include "runtime/realtime_pick.h"
#include "runtime/simulation_thread.h"
#include "ui/accuracy_control.h"
#include "ui/drape_readout.h"
#include "ui/fuzzy_view.h"

namespace neurocloth {

class SceneInfo {
 public:
  SceneInfo() = default;
  // Shares the scene's rule base (read with the scene, not again).
  explicit SceneInfo(const Scene& scene);

  const std::string& name() const { return name_; }
  const std::string& path() const { return path_; }
  std::size_t node_count() const { return node_mass_.size(); }
  // One line on the cloth: its grid, width and mass, and what a resizing
  // (`--size`) kept.
  const std::string& cloth_summary() const { return cloth_summary_; }
  const std::vector<ParameterRange>& ranges() const { return ranges_; }
  // The simulation thread's ranges for what runs now (they change with LoadRules).
  void set_ranges(std::vector<ParameterRange> ranges) { ranges_ = std::move(ranges); }
  const ParameterRange* range(const ParameterId& id) const;
  // What input and module ids index: text from the user is parsed against these.
  const ParameterNames& names() const { return names_; }
  // kg: as the scene was loaded, or for a linguistic material, the node's share
  // of the cloth times the node mass the rule base derives from `inputs` (what
  // the simulation is ramping towards).
  double node_mass(int node, const std::vector<std::pair<std::string, double>>& inputs);
  const Material& material() const { return material_; }
  // The scene's own solver settings and its measured speed/accuracy trade, for
  // the accuracy slider.
  const SolverSettings& solver() const { return solver_; }
  const AccuracyTrade& trade() const { return trade_; }

  // Set when the window replaced the scene's solver to keep real time
  // (realtime_pick.h); cleared when the user takes the scene's own back.
  std::optional<RealtimePick> realtime_pick;

  // The drape test's figures of the running cloth, when the scene has a
  // support (inactive otherwise).
  DrapeReadout& drape() { return drape_; }

  // Set for a linguistic material.
  std::optional<FuzzyView>& fuzzy() { return fuzzy_; }
  const std::optional<FuzzyView>& fuzzy() const { return fuzzy_; }

 private:
  std::string name_, path_, cloth_summary_;
  ParameterNames names_;
  std::vector<ParameterRange> ranges_;
  std::vector<double> node_mass_, mass_share_;
  Material material_;
  SolverSettings solver_;
  AccuracyTrade trade_;
  std::optional<FuzzyView> fuzzy_;
  DrapeReadout drape_;
};

}  // namespace neurocloth
