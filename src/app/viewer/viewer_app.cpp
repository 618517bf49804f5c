#include "app/viewer/viewer_app.h"

#include <cstdio>
#include <thread>

#include "app/viewer/viewer_screenshot.h"
#include "ui/panels.h"
#include "ui/ui_requests.h"

namespace neurocloth {

namespace {

using Clock = std::chrono::steady_clock;

std::string scene_key(const std::string& path, std::size_t nodes) {
  return path + "#" + std::to_string(nodes);
}

}  // namespace

ViewerApp::ViewerApp(ViewerWindow& window, SimulationThread& sim, const Scene& scene,
                     const ViewerOptions& options, const OrbitCamera& camera,
                     std::optional<Script> script)
    : window_(window),
      options_(options),
      sim_(sim),
      scene_info_(scene),
      scene_info_key_(scene_key(scene.path, scene_info_.node_count())),
      camera_(camera),
      start_camera_(camera),
      renderer_(std::make_unique<Renderer>()),
      sink_([this](SimCommand c) { post(std::move(c)); }),
      handler_({sim_, camera_, requests_, sink_, [this](int node) { return node_mass(node); },
                &report_}) {
  if (scene_info_.fuzzy()) copy_text(values_.rules_path, scene_info_.fuzzy()->rules_path());
  if (script) player_.emplace(std::move(*script));
  render_.max_cloth_triangles = kWindowClothTriangles;
  window_.attach(handler_, !player_);
}

ViewerApp::~ViewerApp() = default;

double ViewerApp::node_mass(int node) {
  return scene_info_.node_mass(node, values_.inputs);
}

double ViewerApp::seconds_since_start() const {
  return std::chrono::duration<double>(Clock::now() - start_).count();
}

int ViewerApp::run() {
  start_ = Clock::now();
  for (long frames = 0; !quit_ && !window_.close_requested() && !handler_.quit_requested();
       ++frames) {
    if (options_.lockstep) {
      // The frame sees the simulation exactly where its clock says: the
      // previous frame's Advance (and everything posted before it) is done.
      sim_.wait_for_commands();
      frame(static_cast<double>(frames) * kLockstepFrame);
      // Not waited for here: the simulation steps while this frame is shown.
      sim_.post(Advance{kLockstepFrame});
    } else {
      frame(seconds_since_start());
    }
    if (player_ && player_->done()) quit_ = true;
  }
  return finish();
}

// Under --lockstep every command is applied before the window reads anything
// again (a pick, Space's toggle, the next snapshot), so what a frame sees never
// depends on how fast the simulation thread happened to take the queue.
void ViewerApp::post(SimCommand command) {
  sim_.post(std::move(command));
  if (options_.lockstep) sim_.wait_for_commands();
}

void ViewerApp::frame(double elapsed) {
  elapsed_ = elapsed;
  // Frame rates are wall time whatever clock the script follows.
  const double wall = options_.lockstep ? seconds_since_start() : elapsed;
  window_.poll();
  if (player_) player_->advance(elapsed, *this);
  const std::shared_ptr<const FrameSnapshot> snapshot = sim_.latest();
  const SimulationStatus status = sim_.status();
  follow(status, *snapshot);
  handler_.set_drag_gain(values_.drag_gain);
  handler_.update();
  stats_.sample(wall, status);
  note_errors(elapsed, status);
  carry_out_requests(*snapshot);
  if (window_.minimised()) {
    // Nothing to draw into; the simulation is not waiting for us anyway.
    stats_.skipped();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return;
  }
  draw(status, *snapshot);
  if (last_drawn_ >= 0) stats_.frame(wall, wall - last_drawn_);
  last_drawn_ = wall;
  pace();
}

// Sleeps out the rest of a frame under the fps cap: the core is the simulation's.
// The frames keep to a fixed schedule, so a sleep that overruns is taken back
// from the next one and the cap is the average rate; a frame that ends past its
// slot starts a new schedule rather than a burst of frames to catch up.
void ViewerApp::pace() {
  if (options_.max_fps <= 0) return;
  next_frame_ += 1 / options_.max_fps;
  const double now = seconds_since_start();
  if (next_frame_ <= now) {
    next_frame_ = now;
    return;
  }
  std::this_thread::sleep_for(std::chrono::duration<double>(next_frame_ - now));
}

// Keeps the UI's copy of the scene and its values in step with what runs.
void ViewerApp::follow(const SimulationStatus& status, const FrameSnapshot& snapshot) {
  const std::string key = scene_key(status.scene_path, snapshot.geometry->node_count);
  if (key != scene_info_key_ && !status.scene_path.empty()) {
    scene_info_key_ = key;
    learning_.scene_changed();  // tried once: a failure is shown, not retried every frame
    try {
      scene_info_ = SceneInfo(status.scene ? *status.scene : load_scene(status.scene_path));
      if (scene_info_.fuzzy()) copy_text(values_.rules_path, scene_info_.fuzzy()->rules_path());
    } catch (const std::exception& e) {
      messages_.error = e.what();
    }
  }
  values_.follow(status);
  scene_info_.set_ranges(sim_.parameter_ranges());
  learning_.update(snapshot, sink_);
}

void ViewerApp::carry_out_requests(const FrameSnapshot& snapshot) {
  if (requests_.reset_camera) camera_ = start_camera_;
  if (requests_.frame_camera && snapshot.geometry->node_count > 0) {
    Vec3 lo = snapshot.node(0), hi = lo;
    for (std::size_t i = 1; i < snapshot.geometry->node_count; ++i) {
      lo = lo.cwiseMin(snapshot.node(i));
      hi = hi.cwiseMax(snapshot.node(i));
    }
    const int w = window_.framebuffer_width(), h = window_.framebuffer_height();
    camera_.frame(lo, hi, w > 0 && h > 0 ? double(w) / h : 1.0);
  }
  requests_.reset_camera = requests_.frame_camera = false;
}

void ViewerApp::draw(const SimulationStatus& status, const FrameSnapshot& snapshot) {
  window_.begin_frame();
  const int width = window_.framebuffer_width(), height = window_.framebuffer_height();
  const bool ghosts = learning_.settings().show_ghosts && learning_.ghost_count() > 0;
  renderer_->draw(snapshot, camera_, render_, width, height,
                  ghosts ? &learning_.ghost_points() : nullptr);
  // The picture of the cloth, before the panels are drawn over it (unless asked for).
  if (requests_.screenshot && !requests_.screenshot_panels) take_screenshot();
  PanelContext ctx{status,    snapshot,  scene_info_, values_,   render_,
                   requests_, messages_, sink_,       &learning_};
  draw_controls(ctx);
  window_.draw_ui();
  if (requests_.screenshot && requests_.screenshot_panels) take_screenshot();
  window_.swap();
}

void ViewerApp::take_screenshot() {
  const std::string path = requests_.screenshot_path.empty()
                               ? next_screenshot_path(scene_info_.name())
                               : requests_.screenshot_path;
  requests_.screenshot = requests_.screenshot_panels = false;
  requests_.screenshot_path.clear();
  const int width = window_.framebuffer_width(), height = window_.framebuffer_height();
  try {
    write_screenshot(*renderer_, path, width, height);
    messages_.screenshot = path;
    report_.screenshot(path, width, height);
  } catch (const std::exception& e) {
    show_error(elapsed_, e.what());
  }
}

// Several scripted events may fail in one frame: each is reported as it happens.
void ViewerApp::show_error(double t, const std::string& message) {
  messages_.error = reported_ui_error_ = message;
  report_.error(t, message);
}

// Every error line shown goes into the report too, once.
void ViewerApp::note_errors(double elapsed, const SimulationStatus& status) {
  if (messages_.error != reported_ui_error_) {
    reported_ui_error_ = messages_.error;
    if (!messages_.error.empty()) report_.error(elapsed, messages_.error);
  }
  if (status.last_error != reported_sim_error_) {
    reported_sim_error_ = status.last_error;
    if (!status.last_error.empty()) report_.error(elapsed, "simulation: " + status.last_error);
  }
}

void ViewerApp::set(double t, const std::string& name, double value) {
  // "accuracy" is the Solver panel's slider, not a simulation parameter.
  const std::string refusal = name == "accuracy"
                                  ? request_accuracy(scene_info_, values_, sink_, value)
                                  : request_parameter(scene_info_, values_, sink_, name, value);
  if (!refusal.empty()) show_error(t, refusal);
  report_.parameter(t, name, value, refusal);
}

void ViewerApp::screenshot(const std::string& path, bool panels) {
  requests_.screenshot = true;
  requests_.screenshot_path = path;
  requests_.screenshot_panels = panels;
}

void ViewerApp::probe(double t, int node) {
  report_.probe(t, node, *sim_.latest());
}

void ViewerApp::resize(int width, int height) {
  // As the window system would tell it (0 x 0: minimised), then for real if it can be.
  window_.resized(width, height, width, height);
  window_.request_size(width, height);
}

void ViewerApp::load(const std::string& path) {
  const std::string error = request_scene(path, sink_);
  if (!error.empty()) show_error(elapsed_, error);
}

void ViewerApp::rules(const std::string& path) {
  const std::string error = request_rules(scene_info_, path, sink_);
  if (!error.empty()) show_error(elapsed_, error);
}

void ViewerApp::reference(const ScriptEvent& e) {
  LearningSettings& s = learning_.settings();
  s.reference_fps = static_cast<float>(e.fps);
  s.reference_start = static_cast<float>(e.start);
  copy_text(s.reference_mesh, e.mesh);
  const auto scene = sim_.status().scene;
  const std::string error = scene ? learning_.load_reference(e.name, *scene)
                                  : std::string("reference not loaded: no scene is running");
  if (!error.empty()) show_error(elapsed_, error);
}

// What the Learning panel's buttons do; "wait" (scripts only) holds the window
// until the fit ends, so what a script applies does not depend on the machine.
void ViewerApp::fit(const ScriptEvent& e) {
  std::string error;
  if (e.name == "start") {
    LearningSettings& s = learning_.settings();
    s.online = e.online;
    if (e.max_iterations > 0) s.max_iterations = e.max_iterations;
    if (!e.params.empty()) copy_text(s.params, e.params);
    error = learning_.start_fit(sim_.status().scene);
  } else if (e.name == "stop") {
    learning_.stop_fit();
  } else if (e.name == "wait") {
    learning_.wait_for_fit();
  } else if (e.name == "apply") {
    error = learning_.apply(sink_);
  }
  if (!error.empty()) show_error(elapsed_, error);
}

int ViewerApp::finish() {
  if (!options_.report) return kViewerOk;
  // The report shows the status after everything asked for has been applied.
  sim_.wait_for_commands();
  learning_.update(*sim_.latest(), sink_);  // the ghosts where the cloth ended
  sim_.wait_for_commands();
  const SimulationStatus status = sim_.status();
  note_errors(elapsed_, status);
  report_.learning(learning_);
  try {
    report_.write(*options_.report, status, stats_, scene_info_.names());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "neurocloth: %s\n", e.what());
    return kViewerInputError;
  }
  return kViewerOk;
}

}  // namespace neurocloth
