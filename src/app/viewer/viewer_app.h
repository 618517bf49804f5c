#pragma once
// The window's frame loop. The simulation runs on its own thread; each frame
// takes the newest published snapshot and status (never the live simulation),
// hands input to the InputHandler, draws the snapshot with the Renderer and
// the panels with ImGui. A minimised window draws nothing and the simulation
// goes on. Under --lockstep each frame advances the simulation by one fixed
// step of simulated time and the next frame waits for it.
#include <chrono>
#include <memory>
#include <optional>
#include <string>

#include "app/viewer/viewer_frame_stats.h"
#include "app/viewer/viewer_input.h"
#include "app/viewer/viewer_options.h"
#include "app/viewer/viewer_report.h"
#include "app/viewer/viewer_script_player.h"
#include "app/viewer/viewer_window.h"
#include "render/orbit_camera.h"
#include "render/renderer.h"
#include "runtime/simulation_thread.h"
#include "ui/learning_session.h"
#include "ui/panel_context.h"
#include "ui/scene_info.h"

namespace neurocloth {

class ViewerApp : private ScriptPlayer::Target {
 public:
  // Throws std::runtime_error when the renderer cannot start (shaders).
  // `scene` is what `sim` runs.
  ViewerApp(ViewerWindow& window, SimulationThread& sim, const Scene& scene,
            const ViewerOptions& options, const OrbitCamera& camera, std::optional<Script> script);
  ~ViewerApp() override;
  // Shows in the Solver panel that the window runs another solver than the scene's.
  void set_realtime_pick(const RealtimePick& pick) { scene_info_.realtime_pick = pick; }

  // Runs until the window closes, Esc, or the script ends; writes the report.
  // Returns the exit code.
  int run();

 private:
  // `elapsed`: the script's clock (simulated s under --lockstep, else wall s).
  void frame(double elapsed);
  void post(SimCommand command);  // to the simulation thread
  void pace();
  double seconds_since_start() const;
  void follow(const SimulationStatus& status, const FrameSnapshot& snapshot);
  void carry_out_requests(const FrameSnapshot& snapshot);
  void draw(const SimulationStatus& status, const FrameSnapshot& snapshot);
  void take_screenshot();
  void note_errors(double elapsed, const SimulationStatus& status);
  void show_error(double t, const std::string& message);
  double node_mass(int node);
  int finish();

  // ScriptPlayer::Target: scripted input goes where real input goes.
  void cursor(double x, double y) override { handler_.cursor(x, y); }
  void button(int b, bool pressed, int mods) override { handler_.button(b, pressed, mods); }
  void scroll(double steps) override {
    handler_.scroll(steps);
    window_.scripted_wheel(steps);
  }
  void key(int k, int mods) override { handler_.key(k, mods); }
  void set(double t, const std::string& name, double value) override;
  void screenshot(const std::string& path, bool panels) override;
  void probe(double t, int node) override;
  void resize(int width, int height) override;
  void load(const std::string& path) override;
  void rules(const std::string& path) override;
  void reference(const ScriptEvent& e) override;
  void fit(const ScriptEvent& event) override;
  void quit() override { quit_ = true; }

  ViewerWindow& window_;
  ViewerOptions options_;
  SimulationThread& sim_;
  SceneInfo scene_info_;
  std::string scene_info_key_;  // path and node count the SceneInfo was made for
  UiValues values_;
  RenderOptions render_;
  WindowRequests requests_;
  UiMessages messages_;
  LearningSession learning_;
  OrbitCamera camera_, start_camera_;
  std::unique_ptr<Renderer> renderer_;
  ViewerReport report_;
  FrameStats stats_;
  CommandSink sink_;  // to the simulation thread
  InputHandler handler_;
  std::optional<ScriptPlayer> player_;
  bool quit_ = false;
  std::chrono::steady_clock::time_point start_;  // the first frame
  double elapsed_ = 0;      // the script's clock at this frame (simulated s under --lockstep)
  double last_drawn_ = -1;  // wall s
  double next_frame_ = 0;   // wall s: when the fps cap lets the next frame start
  std::string reported_ui_error_, reported_sim_error_;
};

}  // namespace neurocloth
