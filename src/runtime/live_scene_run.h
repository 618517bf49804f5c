#pragma once
// The inside of LiveScene shared by the files that hold it: live_scene.cpp
// (the commands of the running scene) and live_scene_material.cpp (what
// changes its material from outside: a new rule base, an applied fit).
#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "runtime/live_scene.h"

namespace neurocloth {
namespace live_detail {

// A number as a message shows it.
std::string number(double v);
// The first wind module's declaration index, or -1: the one whose mean wind
// the status reports.
int first_wind(const ParameterNames& names);
// The scene's simulation as the thread runs it (live_scene.cpp).
Simulation live_simulation(Scene scene);

}  // namespace live_detail

// Built in one piece so that a scene that fails to load or build replaces
// nothing.
struct LiveScene::Run {
  // The scene as it was loaded, shared with whoever asks (the UI builds its
  // view of the scene from it, not from the file again).
  std::shared_ptr<const Scene> loaded;
  Scene scene;  // what runs: LoadRules replaces its rule base
  Simulation sim;
  ParameterNames names;
  std::vector<ParameterRange> ranges;
  std::shared_ptr<const SceneGeometry> geometry;

  explicit Run(std::shared_ptr<const Scene> s)
      : loaded(std::move(s)),
        scene(*loaded),
        sim(live_detail::live_simulation(scene)),
        names(parameter_names(scene)),
        ranges(parameter_ranges(scene)),
        geometry(make_geometry(scene)) {}

  const FuzzyMaterial* rules() const {
    return scene.fuzzy_material ? scene.fuzzy_material->rules.get() : nullptr;
  }

  // The module the scene declared `index`-th (a force module: only those have
  // live parameters), found as the same occurrence of its type among the
  // network's force modules, which keep the declaration order.
  // Its position in the network's force modules, or -1.
  int force_module(int index) const {
    const std::string& type = names.modules[index];
    auto occurrence = std::count(names.modules.begin(), names.modules.begin() + index, type);
    const auto& modules = sim.network().force_modules;
    for (std::size_t k = 0; k < modules.size(); ++k)
      if (modules[k]->type() == type && occurrence-- == 0) return static_cast<int>(k);
    return -1;
  }
};

}  // namespace neurocloth
