#pragma once
// What happened in a window session, for tests and scripts (--report FILE):
// nodes picked, dragged and pinned with their positions read from the
// published snapshots (not the picture), parameters asked for and what the
// status then showed, probes, screenshots, errors, frame and step rates.
#include <string>

#include <nlohmann/json.hpp>

#include "app/viewer/viewer_frame_stats.h"
#include "core/scene/frame_snapshot.h"
#include "runtime/simulation_thread.h"
#include "ui/learning_session.h"

namespace neurocloth {

// The report names nodes as the scene does: by their vertex in a mesh's file
// (SceneGeometry::numbering), whatever order the simulation keeps them in.
class ViewerReport {
 public:
  // A left press on simulation node `node`: -1 when it missed the cloth.
  void picked(int node, double x, double y, const FrameSnapshot& snapshot);
  // `target`: where the cursor pulled the node last.
  void released(int node, const Vec3& target, const FrameSnapshot& snapshot);
  void pinned(int node, bool pinned, const FrameSnapshot& snapshot);
  // A set request; `refusal` is empty when it was posted.
  void parameter(double t, const std::string& name, double value, const std::string& refusal);
  // A script's probe of the file's `vertex` (node index as scenes count them).
  void probe(double t, int vertex, const FrameSnapshot& snapshot);
  void screenshot(const std::string& path, int width, int height);
  void error(double t, const std::string& message);
  // The Learning panel at the end: the reference, its ghost points at the last
  // snapshot, the fit's progress and what was applied.
  void learning(const LearningSession& session);

  // Writes the report with the final status (each set's name read against
  // `names`, the running scene's); throws std::runtime_error naming `path`.
  void write(const std::string& path, const SimulationStatus& status, const FrameStats& stats,
             const ParameterNames& names = {}) const;

 private:
  nlohmann::json picks_ = nlohmann::json::array(), drags_ = nlohmann::json::array(),
                 pins_ = nlohmann::json::array(), sets_ = nlohmann::json::array(),
                 probes_ = nlohmann::json::array(), screenshots_ = nlohmann::json::array(),
                 errors_ = nlohmann::json::array();
  nlohmann::json learning_ = nlohmann::json::object();
};

}  // namespace neurocloth
