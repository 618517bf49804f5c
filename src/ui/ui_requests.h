#pragma once
// What the UI asks of the simulation, checked here first (validate at the
// boundary): a value out of range, a scene or rule base that does not read is
// refused on the UI side with a message naming why (range, file, line), and
// nothing is posted. Panels and the window's script player both go through
// these, so a scripted change is handled exactly as a typed one.
#include <string>

#include "ui/panel_context.h"

namespace neurocloth {

// Posts SetParameter{id, value} and mirrors it in `values` when it is valid;
// otherwise returns why not (e.g. "viscosity = 5 refused: valid range 0 .. 2 N s/m").
// An empty string means it was posted.
std::string request_parameter(const SceneInfo& scene, UiValues& values, const CommandSink& post,
                              const ParameterId& id, double value);
// The same for a name typed or scripted ("gravity.y", "input.mass"), parsed
// against the scene's names first: an unknown one is refused, quoted.
std::string request_parameter(const SceneInfo& scene, UiValues& values, const CommandSink& post,
                              const std::string& name, double value);

// The accuracy slider's request (and a script's "set" of "accuracy"): the
// cheapest setting the scene's measured trade says keeps the position error
// within `accuracy` (a fraction of the cloth's size), posted as one SetSolver
// and mirrored in `values`. Returns why not when the scene has no trade or the
// trade cannot vouch for that accuracy (naming the trade file).
std::string request_accuracy(const SceneInfo& scene, UiValues& values, const CommandSink& post,
                             double accuracy);

// Reads the scene file here (so a bad one is named at once), then posts
// LoadScene with the scene read: the file is read once. Returns the error, or
// "" when posted.
std::string request_scene(const std::string& path, const CommandSink& post);

// A triangle mesh from an OBJ file as an obstacle (a "mesh" module, scaled by
// `scale`, its origin moved to `translate`; docs/scenes.md), added to
// `running` (the scene as the thread loaded it): the module is read here
// through the scene reader's own "mesh" reading, so a bad file is refused with
// the reader's message naming it, and nothing is posted. Otherwise posts
// LoadScene with the scene and its new obstacle (the run starts over, as a
// Load does), refreshes `info` from it, and returns "". A relative path is
// taken from the working directory.
std::string request_obstacle(const Scene& running, SceneInfo& info, const std::string& obj_path,
                             double scale, const Vec3& translate, const CommandSink& post);

// Reads the rule base here, installs it in `scene`'s FuzzyView and posts
// LoadRules. Returns the error, or "" when posted.
std::string request_rules(SceneInfo& scene, const std::string& path, const CommandSink& post);

// "0 .. 2 N s/m" for a tooltip or a refusal.
std::string range_text(const ParameterRange& range);

}  // namespace neurocloth
