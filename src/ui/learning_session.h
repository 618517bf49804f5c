#pragma once
// What the Learning panel keeps between frames, apart from its widgets: the
// reference motion loaded (read here, on the UI thread, so a bad file is named
// at once and the running scene never sees it), the ghost points it puts
// beside the cloth at the snapshot's time, and the fit running on its own
// worker thread (fit_worker.h), polled once a frame. No ImGui here: the window's
// scripts drive the same calls the panel's buttons do.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "core/scene/frame_snapshot.h"
#include "learn/motion/reference_motion.h"
#include "runtime/fit_worker.h"
#include "ui/panel_context.h"

namespace neurocloth {

// The panel's own settings (plain values its widgets edit).
struct LearningSettings {
  std::array<char, 512> reference_path{};
  // As fit --reference-fps, --reference-start, --reference-mesh: a frame
  // sequence's (PLY / XYZ files) or a PC2 cache's frames per second (0: not
  // given), its first frame's time (s), a PC2 / MDD cache's OBJ mesh.
  float reference_fps = 0;
  float reference_start = 0;
  std::array<char, 512> reference_mesh{};
  // A point cloud's comparison, as fit --chamfer, --robust, --robust-scale.
  bool one_sided = false;
  int robust = 0;  // RobustLoss: none, huber, cauchy
  float robust_scale = 0.01f;
  std::array<char, 512> params{};  // comma-separated, as `fit --params`
  int optimizer = 0;               // 0 lbfgs, 1 gradient descent
  int max_iterations = 30;
  bool online = false;  // online adaptation through the reference instead of the batch fit
  int window = 50;      // online: steps per window
  float learning_rate = 0.05f;
  bool follow = false;  // online: apply every update to the running cloth as it comes
  bool show_ghosts = true;
  LearningSettings();
};

class LearningSession {
 public:
  explicit LearningSession(std::function<void(int)> on_row = {}) : worker_(std::move(on_row)) {}

  // Reads a reference for `scene`'s cloth (read_reference: a recording, a
  // markers or cloud CSV, a PLY / XYZ frame sequence, a PC2 / MDD cache),
  // with the settings' frame rate, start and mesh. On failure the reference
  // loaded before stays, and the error (one line naming the file, line and
  // field) is returned and kept in error().
  std::string load_reference(const std::string& path, const Scene& scene);
  // The scene changed (a load): its nodes are not the reference's, so the
  // reference goes, and a fit of the old scene is stopped.
  void scene_changed();

  // Once a frame: the ghost points at the snapshot's time and the fit's
  // newest progress; under `follow`, posts each new online update.
  void update(const FrameSnapshot& snapshot, const CommandSink& post);

  // Starts a fit of `scene` (as loaded) to the reference with the settings.
  std::string start_fit(std::shared_ptr<const Scene> scene);
  void stop_fit() { worker_.stop(); }
  // Posts the newest fitted parameters to the running cloth (ApplyFit); "" or why not.
  std::string apply(const CommandSink& post);
  void wait_for_fit() const { worker_.wait(); }

  LearningSettings& settings() { return settings_; }
  const std::shared_ptr<const ReferenceMotion>& reference() const { return reference_; }
  const std::string& error() const { return error_; }
  void clear_error() { error_.clear(); }
  const FitProgress& progress() const { return progress_; }
  bool fit_running() const { return worker_.running(); }

  // The ghosts of the last update: x, y, z per point (m), for the renderer.
  const std::vector<float>& ghost_points() const { return ghost_points_; }
  std::size_t ghost_count() const { return ghost_points_.size() / 3; }
  double ghost_time() const { return ghost_time_; }
  bool reference_ended() const { return reference_ended_; }
  // RMS distance (m) from each ghost to the running cloth's node of the same
  // file index (mapped through the scene's NodeNumbering).
  double ghost_rms_m() const { return ghost_rms_m_; }
  // What the last Apply sent, one line ("" before any).
  const std::string& applied() const { return applied_; }
  int applied_count() const { return applied_count_; }

 private:
  void post_outcome(const FitOutcome& outcome, const CommandSink& post);

  LearningSettings settings_;
  std::shared_ptr<const ReferenceMotion> reference_;
  std::string error_;
  FitWorker worker_;
  FitProgress progress_;
  long seen_serial_ = -1;
  std::shared_ptr<const FitOutcome> followed_;  // the last outcome `follow` posted
  std::vector<float> ghost_points_;
  double ghost_time_ = 0, ghost_rms_m_ = 0;
  bool reference_ended_ = false;
  std::string applied_;
  int applied_count_ = 0;
};

}  // namespace neurocloth
