#pragma once
// A scene file (JSON, format in docs/scenes.md) read into everything needed to
// build and run a simulation. One scene definition serves the app, the tests and
// the benchmarks.
#include <string>
#include <vector>

#include <map>
#include <memory>
#include <optional>

#include "core/io/asset_paths.h"
#include "core/modules/module_specs.h"
#include "core/network/cloth_network.h"
#include "core/scene/grid_builder.h"
#include "core/scene/measured_material.h"
#include "core/simulation/simulation.h"
#include "core/simulation/solver_settings.h"

namespace neurocloth {

class FuzzyMaterial;
struct ElementWeights;

struct Scene {
  std::string path;  // the file it came from ("" when parsed from text)
  std::string name;
  ClothTopology topology;
  std::optional<GridSpec> grid;  // set when the cloth is a grid
  std::vector<int> pins;         // node indices
  // Every unpinned node's velocity at t = 0 ("cloth.initial_velocity"; a
  // fitted throw's, docs/learning.md "Control").
  Vec3 initial_velocity = Vec3::Zero();
  Material material;
  // Set when the material came from a rule base ({"rules", "inputs"} or
  // {"preset"}): what to re-derive from when an input changes. The rule base
  // is read once, with the scene, and shared: it never changes, and a copy of
  // the scene (the viewer's, a reset's) need not read the file again.
  struct FuzzySource {
    std::string rules_path;
    std::shared_ptr<const FuzzyMaterial> rules;
    std::map<std::string, double> inputs;
    std::vector<std::string> notes;  // clamped inputs, defaulted outputs
  };
  std::optional<FuzzySource> fuzzy_material;
  // Set when the material was given in measured units ({"measured": ...}):
  // what `material` was derived from, for this topology (measured_material.h),
  // and what the cloth could not represent of it.
  std::optional<MeasuredMaterial> measured_material;
  std::vector<std::string> material_notes;
  SpringFunction spring_function;
  Vec3 gravity = Vec3(0, -9.81, 0);
  SolverSettings solver;
  // The declared modules, in file order; none unless the file has "modules".
  std::vector<ModuleDeclaration> modules;
  // Per-element weights from the side file the scene names under
  // "element_weights" (a fit's output, element_weights.h): applied over the
  // material's when the network is built. Read once and shared, like the rule base.
  std::shared_ptr<const ElementWeights> element_weights;
  // Set by resized_grid: the grid the cloth had before, and what it weighed
  // there (kg), so a panel can say what the resizing kept.
  struct Resizing {
    int rows = 0, cols = 0;
    double mass = 0;
  };
  std::optional<Resizing> resized_from;

  // The bare network: springs, masses, gravity, pins (no modules).
  ClothNetwork build_network() const;
  ClothState initial_state() const;  // rest positions, initial_velocity off the pins
  // The network with the scene's modules built and attached: what to run.
  Simulation make_simulation() const;
};

// The same cloth on an n x n grid with all three spring families, pinned (if
// it was pinned) at the two corners of its first row (which a pin_motion module
// then moves), with the scene's modules and solver: what `--size` runs and the
// benchmarks time at several sizes. The cloth keeps its width (its longer side)
// and its mass per area, so a square cloth weighs what it did: a material in
// words already weighs by area, a numeric one gets node_mass = mass / n^2.
// Spring constants and damping per spring are kept (on a square grid the
// sheet's in-plane stiffness and damping per unit strain do not depend on the
// spacing; docs/scenes.md, "Resizing"). `scene` must be a grid scene; n >= 2.
Scene resized_grid(const Scene& scene, int n);

// kg: the cloth's node masses summed as its network has them (element
// weights and a rule base's shares by area included).
double cloth_mass(const Scene& scene);

// The names a scene's parameter ids index: its rule base's inputs and its modules.
ParameterNames parameter_names(const Scene& scene);

// Reading (scene_reader.cpp). Throws InputError (file, field, line) for
// anything wrong; never returns a half-read scene.
Scene load_scene(const std::string& path);
// `path` is used for messages and to resolve relative paths (OBJ files).
Scene parse_scene(const std::string& text, const std::string& path);

}  // namespace neurocloth
