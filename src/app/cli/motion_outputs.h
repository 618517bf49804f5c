#pragma once
// What `simulate --record FILE` and `--export-pc2 FILE` write: the cloth's
// positions at every frame time k / fps, in the file's node order, streamed to
// a recording (src/learn/motion/motion_recording.h) and a PC2 point cache with its
// rest mesh (src/learn/pc2_writer.h). Both files appear only when the run has
// ended and both are complete; a bad option or an unwritable path is refused
// before the run starts.
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/cli/commands.h"
#include "core/scene/scene.h"
#include "learn/motion/motion_recording.h"
#include "learn/motion/pc2_writer.h"

namespace neurocloth {

// Refuses (InputError naming `option`) an output path that is a directory or
// one of the command's input files (`inputs`; empty ones are skipped): the
// run would end by failing to write, or by overwriting what it read.
void check_output_path(const char* option, const std::string& path,
                       const std::vector<std::string>& inputs);
// The files `scene` was read from: the scene, its rule base and its side file.
std::vector<std::string> input_files(const Scene& scene);

class MotionOutputs {
 public:
  // Checks the options (InputError naming the option) and opens the files.
  MotionOutputs(const SimulateOptions& options, const Scene& scene);

  double fps() const { return fps_; }
  // Adds `state`, the cloth at time t, as the next frame. A state a file
  // must not hold (a coordinate beyond kMaxReferenceCoordinate: a run blowing
  // up between two divergence checks) ends the frames there, said at the end.
  void frame(double t, const ClothState& state);
  // After the run: keeps the frames up to `sim`'s time (a diverged run rolled
  // back to its last good state, and frames after it go).
  void keep_until(const Simulation& sim);
  // What RESULT.json says of the frames ("motion").
  nlohmann::json result_json() const;
  // Writes the files into place; returns the lines to print.
  std::vector<std::string> finish(const Simulation& sim);

 private:
  const Scene& scene_;
  double fps_ = 60;
  std::optional<RecordingWriter> recording_;
  std::optional<Pc2Writer> pc2_;
  std::string mesh_path_;
  std::vector<double> times_;    // of the frames kept so far
  std::size_t dropped_ = 0;      // frames after a divergence's rollback
  std::string stopped_;          // why frames stopped before the run did
  std::vector<Vec3> positions_;  // one frame in file order, reused
};

}  // namespace neurocloth
