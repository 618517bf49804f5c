#pragma once
// What `simulate --record FILE` and `--export-pc2 FILE` write: the cloth's
// positions at every frame time k / fps, in the file's node order, streamed to
// a recording (src/learn/motion/motion_recording.h) and a PC2 point cache with its
// rest mesh (src/learn/pc2_writer.h). `--export-pc2 RUN.pc2` also writes every
// collider beside them, so Blender plays the whole scene: RUN.obstacleK.obj
// (the K-th collider of the scene, K from 1: a mesh obstacle's own triangles,
// the others tessellated as the renderer draws them, a plane as a square
// around the cloth) where it is at t = 0, and for one that moves or deforms
// RUN.obstacleK.pc2, its vertices at the cloth's frames (the same rate and
// layout). Every file appears only when the run has ended and all are
// complete; a bad option or an unwritable path is refused before the run starts.
#include <array>
#include <cstdint>
#include <memory>
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
// The files `scene` was read from: the scene, its rule base, its side file
// and its obstacles' meshes and caches.
std::vector<std::string> input_files(const Scene& scene);

// "run.pc2" and collider K (from 1) -> "run.obstacleK.obj" (`extension` ".obj")
// or "run.obstacleK.pc2"; `pc2_path` ends in ".pc2" (pc2_mesh_path checks).
std::string obstacle_path(const std::string& pc2_path, std::size_t k, const char* extension);

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

  // One collider as --export-pc2 writes it.
  struct Obstacle {
    std::size_t module = 0;  // its index in scene.modules
    std::string type;        // as the scene declares it ("box", "mesh", ...)
    std::string obj_path;
    std::string pc2_path;  // "" when it neither moves nor deforms
    // Its vertices in its shape frame, in the OBJ's order, and its triangles.
    // A mesh obstacle's are its own (those some triangle uses: a vertex of no
    // face would shift a Blender import's order); `source` is then the mesh
    // vertex of each, for a deforming one.
    std::vector<Vec3> shape;
    std::vector<std::int32_t> source;
    std::vector<std::array<std::int32_t, 3>> triangles;
    std::unique_ptr<Pc2Writer> pc2;  // when it moves or deforms (a writer cannot move)
  };
  // The scene's colliders as obstacles, named after `pc2_path`.
  void add_obstacles(const std::string& pc2_path);
  // Where obstacle `ob`'s vertices are at time t, into `out`.
  void place(const Obstacle& ob, double t, std::vector<Vec3>& out);
  std::vector<Obstacle> obstacles_;
  std::vector<Vec3> deformed_, placed_;  // scratch, reused
};

}  // namespace neurocloth
