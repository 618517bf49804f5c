#include "ui/learning_session.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <sstream>

#include "learn/motion/read_reference.h"
#include "learn/motion/reference_pose.h"
#include "ui/ui_values.h"

namespace neurocloth {

namespace {

std::vector<std::string> split_params(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    const auto b = item.find_first_not_of(" \t");
    const auto e = item.find_last_not_of(" \t");
    if (b != std::string::npos) out.push_back(item.substr(b, e - b + 1));
  }
  return out;
}

}  // namespace

LearningSettings::LearningSettings() {
  copy_text(params, "spring_constant,viscosity");
}

std::string LearningSession::load_reference(const std::string& path, const Scene& scene) {
  try {
    ReferenceOptions o;
    o.fps = settings_.reference_fps;
    o.start = settings_.reference_start;
    o.mesh = settings_.reference_mesh.data();
    o.scene_positions = file_order_positions(scene);
    reference_ = std::make_shared<const ReferenceMotion>(
        read_reference(path, scene.topology.rest_positions.size(), o));
  } catch (const std::exception& e) {
    error_ = std::string("reference not loaded: ") + e.what();
    return error_;
  }
  copy_text(settings_.reference_path, path);
  error_.clear();
  return "";
}

void LearningSession::scene_changed() {
  if (reference_) error_ = "reference unloaded: the scene changed (load it again for this scene)";
  reference_.reset();
  ghost_points_.clear();
  worker_.stop();
}

void LearningSession::update(const FrameSnapshot& snapshot, const CommandSink& post) {
  ghost_points_.clear();
  ghost_rms_m_ = 0;
  reference_ended_ = false;
  ghost_time_ = snapshot.time;
  if (reference_) {
    const ReferencePose pose = reference_pose(*reference_, snapshot.time);
    reference_ended_ = pose.ended;
    double sum = 0;
    std::size_t matched = 0;
    for (const Vec3& p : pose.positions)
      ghost_points_.insert(ghost_points_.end(), {float(p.x()), float(p.y()), float(p.z())});
    // The distance to the cloth where a point names its node (a cloud's do
    // not), when the snapshot carries the cloth's geometry to number them by
    // (a default snapshot carries none).
    static const SceneGeometry kNoCloth;
    const SceneGeometry& g = snapshot.geometry ? *snapshot.geometry : kNoCloth;
    for (std::size_t k = 0; k < pose.nodes.size(); ++k) {
      const Vec3& p = pose.positions[k];
      const std::int32_t file = pose.nodes[k];
      if (file < 0 || static_cast<std::size_t>(file) >= g.node_count) continue;
      sum += (snapshot.node(static_cast<std::size_t>(g.numbering.node(file))) - p).squaredNorm();
      ++matched;
    }
    if (matched > 0) ghost_rms_m_ = std::sqrt(sum / double(matched));
  }
  if (worker_.serial() != seen_serial_) {
    seen_serial_ = worker_.serial();
    progress_ = worker_.progress();
  }
  if (settings_.follow && progress_.online && progress_.outcome && progress_.outcome != followed_) {
    followed_ = progress_.outcome;
    post_outcome(*followed_, post);
  }
}

std::string LearningSession::start_fit(std::shared_ptr<const Scene> scene) {
  FitJob job;
  job.scene = std::move(scene);
  job.reference = reference_;
  job.settings.params = split_params(settings_.params.data());
  job.settings.chamfer.one_sided = settings_.one_sided;
  job.settings.chamfer.robust = static_cast<RobustLoss>(std::clamp(settings_.robust, 0, 2));
  job.settings.chamfer.scale = settings_.robust_scale;
  if (job.settings.params.empty()) return "name at least one parameter to fit";
  if (!(settings_.robust_scale > 0) || !(settings_.robust_scale <= 1e3))
    return "robust scale " + std::to_string(settings_.robust_scale) +
           " refused: a distance in m in (0, 1000]";
  job.method =
      settings_.optimizer == 1 ? OptimizerMethod::gradient_descent : OptimizerMethod::lbfgs;
  job.max_iterations = settings_.max_iterations;
  job.online = settings_.online;
  if (settings_.window < 1) return "the online window must be at least 1 step";
  if (!(settings_.learning_rate > 0 && settings_.learning_rate <= 10))
    return "the learning rate must lie in (0, 10]";
  job.online_settings = {static_cast<std::size_t>(settings_.window),
                         static_cast<double>(settings_.learning_rate)};
  followed_.reset();
  const std::string why = worker_.start(std::move(job));
  if (why.empty()) {
    seen_serial_ = worker_.serial();
    progress_ = worker_.progress();
  }
  return why;
}

std::string LearningSession::apply(const CommandSink& post) {
  // The newest, not the frame's copy: a script may apply right after a wait.
  const FitProgress now = worker_.progress();
  if (!now.outcome) return "nothing to apply: no fit has produced parameters yet";
  post_outcome(*now.outcome, post);
  return "";
}

void LearningSession::post_outcome(const FitOutcome& outcome, const CommandSink& post) {
  post(outcome.command);
  const Material& m = outcome.command.material;
  char line[160];
  std::snprintf(line, sizeof line,
                "spring %.4g, shear %.4g, bend %.4g N/m, mass %.4g kg, "
                "viscosity %.4g, friction %.4g",
                m.spring_constant, m.shear(), m.bend(), m.node_mass, m.viscosity, m.friction);
  applied_ = line;
  if (!outcome.words.empty()) {  // a material in words: its inputs, not numbers
    applied_.clear();
    for (const std::string& w : outcome.words)
      applied_ += (applied_.empty() ? "" : "; ") + w;
  }
  if (const std::size_t n = outcome.command.module_parameters.size(); n > 0)
    applied_ += "; " + std::to_string(n) + " module parameter(s)";
  for (const std::string& n : outcome.not_applied)
    applied_ += "; not applied: " + n;
  ++applied_count_;
}

}  // namespace neurocloth
