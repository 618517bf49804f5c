#pragma once
// The simulation thread exactly as the window runs it, without the window:
// the reference for "the simulation never waits for the renderer" (steps per
// second with the window should match these).
#include <string>

#include "app/viewer/viewer_options.h"
#include "core/scene/scene.h"

namespace neurocloth {

// Runs for options.sim_only wall seconds, prints the medians on one line and
// writes options.report (same layout as the window's) when given.
int run_sim_only(const Scene& scene, const ViewerOptions& options);

}  // namespace neurocloth
