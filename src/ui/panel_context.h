#pragma once
// What every panel is handed for one frame. Panels read the published status
// and snapshot, edit the UI's own values, and post commands; anything they
// need of the window (a screenshot, the camera) is asked for in WindowRequests.
#include <functional>
#include <string>

#include "core/scene/frame_snapshot.h"
#include "render/renderer.h"
#include "runtime/sim_command.h"
#include "runtime/simulation_thread.h"
#include "ui/scene_info.h"
#include "ui/ui_values.h"

namespace neurocloth {

using CommandSink = std::function<void(SimCommand)>;
class LearningSession;

// Carried out by the window before its next frame.
struct WindowRequests {
  bool screenshot = false;
  std::string screenshot_path;     // empty: a fresh name in the working directory
  bool screenshot_panels = false;  // the whole window, controls included
  bool frame_camera = false;
  bool reset_camera = false;
};

// One line each, shown in red/grey at the top of the controls.
struct UiMessages {
  std::string error;       // the UI's own last refusal or failed load
  std::string screenshot;  // the file the last screenshot went to
};

struct PanelContext {
  const SimulationStatus& status;
  const FrameSnapshot& snapshot;
  SceneInfo& scene;
  UiValues& values;
  RenderOptions& render;
  WindowRequests& requests;
  UiMessages& messages;
  CommandSink post;
  // The Learning panel's reference and fit (null: no Learning panel).
  LearningSession* learning = nullptr;
};

}  // namespace neurocloth
