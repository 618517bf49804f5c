#include "app/cli/motion_outputs.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "core/scene/element_weights.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {
namespace {

// Frames a run of `seconds` records at `fps`: frame 0 and one per 1 / fps.
double planned_frames(double seconds, double fps) {
  return std::floor(seconds * fps) + 1;
}

bool same_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::equivalent(a, b, ec) && !ec) return true;  // links, "./x" and "x", ...
  const fs::path x = fs::absolute(a, ec).lexically_normal();
  if (ec) return false;
  return x == fs::absolute(b, ec).lexically_normal() && !ec;
}

}  // namespace

void check_output_path(const char* option, const std::string& path,
                       const std::vector<std::string>& inputs) {
  if (path.empty()) return;
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError("command line", option, "'" + path + "' is a folder, not a file to write");
  // The write renames a new file over the path: over /dev/null or a FIFO it
  // would replace the device itself.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw InputError("command line", option,
                     "'" + path + "' exists and is not a regular file (a device, FIFO or socket)");
  for (const std::string& in : inputs)
    if (!in.empty() && same_file(path, in))
      throw InputError("command line", option,
                       "'" + path + "' is " + (in == path ? "" : "'" + in + "', ") +
                           "a file this command reads: writing it would destroy it");
}

std::vector<std::string> input_files(const Scene& scene) {
  std::vector<std::string> files = {scene.path};
  if (scene.fuzzy_material) files.push_back(scene.fuzzy_material->rules_path);
  if (scene.element_weights) files.push_back(scene.element_weights->path);
  return files;
}

MotionOutputs::MotionOutputs(const SimulateOptions& o, const Scene& scene) : scene_(scene) {
  const char* option = o.record ? "--record" : "--export-pc2";
  if (o.record_fps) {
    fps_ = *o.record_fps;
    if (!(fps_ > 0) || !std::isfinite(fps_) || fps_ > 10000)
      throw InputError("command line", "--record-fps",
                       "must be a number > 0 and at most 10000 (frames per simulated second)");
  }
  const std::size_t nodes = scene.topology.rest_positions.size();
  const double frames = planned_frames(o.seconds, fps_);
  if (frames * static_cast<double>(nodes) > static_cast<double>(kMaxReferenceObservations))
    throw InputError("command line", option,
                     "--seconds " + std::to_string(o.seconds) + " at " + std::to_string(fps_) +
                         " frames per second is " + std::to_string(frames) + " frames of " +
                         std::to_string(nodes) + " nodes: more than the " +
                         std::to_string(kMaxReferenceObservations) +
                         " node positions a recording may hold; lower --record-fps");
  if (frames > static_cast<double>(kMaxReferenceFrames))
    throw InputError("command line", option,
                     "--seconds " + show_number(o.seconds) + " at " + show_number(fps_) +
                         " frames per second is " + show_number(frames) +
                         " frames: more than the " + std::to_string(kMaxReferenceFrames) +
                         " a recording may hold; lower --record-fps");
  if (o.export_pc2) mesh_path_ = pc2_mesh_path(*o.export_pc2);
  // Two outputs at one path would leave only the one written last.
  const std::vector<std::string> paths = {o.out, o.record.value_or(""), o.export_pc2.value_or(""),
                                          mesh_path_};
  for (std::size_t i = 0; i < paths.size(); ++i)
    for (std::size_t j = i + 1; j < paths.size(); ++j)
      if (!paths[i].empty() && !paths[j].empty() && same_file(paths[i], paths[j]))
        throw InputError("command line", option,
                         "'" + paths[i] + "' is named for two outputs; give each its own file");
  const std::vector<std::string> inputs = input_files(scene);
  check_output_path("--record", o.record.value_or(""), inputs);
  check_output_path("--export-pc2", o.export_pc2.value_or(""), inputs);
  check_output_path("--export-pc2", mesh_path_, inputs);
  if (o.record) recording_.emplace(*o.record, RecordingInfo{scene.name, nodes, fps_});
  if (o.export_pc2) pc2_.emplace(*o.export_pc2, nodes);
  positions_.resize(nodes);
}

void MotionOutputs::frame(double t, const ClothState& s) {
  if (!stopped_.empty()) return;
  for (std::size_t k = 0; k < positions_.size(); ++k) {
    positions_[k] =
        s.position(static_cast<std::size_t>(scene_.topology.numbering.node(static_cast<int>(k))));
    if (!reference_position_ok(positions_[k])) {
      char buf[200];
      std::snprintf(buf, sizeof buf,
                    "frames stop before t = %.6g s: node %zu is beyond 1e6 m from the origin "
                    "there (a run blowing up?)",
                    t, k);
      stopped_ = buf;
      return;
    }
  }
  if (recording_) recording_->add_frame(t, positions_);
  if (pc2_) pc2_->add_frame(positions_);
  times_.push_back(t);
}

void MotionOutputs::keep_until(const Simulation& sim) {
  std::size_t keep = times_.size();
  while (keep > 0 && times_[keep - 1] > sim.time())
    --keep;
  dropped_ += times_.size() - keep;
  times_.resize(keep);
  if (recording_) recording_->drop_frames_after(sim.time());
  if (pc2_) pc2_->keep_first(keep);
}

std::vector<std::string> MotionOutputs::finish(const Simulation& sim) {
  std::vector<std::string> lines;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "%zu frame%s at %g per second, t = 0 to %.6g s, nodes in file order", times_.size(),
                times_.size() == 1 ? "" : "s", fps_, times_.empty() ? 0.0 : times_.back());
  const std::string frames = buf;
  if (recording_) {
    recording_->finish();
    lines.push_back("recorded " + recording_->path() + ": " + frames);
  }
  if (pc2_) {
    write_rest_mesh_obj(scene_.topology, mesh_path_);
    pc2_->finish();
    lines.push_back("exported " + pc2_->path() + " (" + frames + ") and its rest mesh " +
                    mesh_path_ + " (docs/learning.md: playing it in Blender)");
  }
  if (!stopped_.empty()) lines.push_back(stopped_);
  if (sim.status() != RunStatus::ok) {
    std::snprintf(buf, sizeof buf,
                  "the run diverged: the frames stop at the last good state (t = %.6g s)%s",
                  sim.time(), dropped_ ? "; frames recorded after it were dropped" : "");
    lines.emplace_back(buf);
  }
  return lines;
}

nlohmann::json MotionOutputs::result_json() const {
  nlohmann::json j = {{"fps", fps_},
                      {"frames", times_.size()},
                      {"last_frame_time", times_.empty() ? 0.0 : times_.back()}};
  if (!stopped_.empty()) j["stopped"] = stopped_;
  if (recording_) j["record"] = recording_->path();
  if (pc2_) {
    j["pc2"] = pc2_->path();
    j["pc2_mesh"] = mesh_path_;
  }
  return j;
}

}  // namespace neurocloth
