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

// Reads the rule base here, installs it in `scene`'s FuzzyView and posts
// LoadRules. Returns the error, or "" when posted.
std::string request_rules(SceneInfo& scene, const std::string& path, const CommandSink& post);

// "0 .. 2 N s/m" for a tooltip or a refusal.
std::string range_text(const ParameterRange& range);

}  // namespace neurocloth
