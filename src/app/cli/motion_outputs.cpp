#include "app/cli/motion_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <ostream>
#include <stdexcept>

#include "core/io/input_error.h"
#include "core/io/physical_limits.h"
#include "core/io/text_file.h"
#include "core/modules/collider_motion.h"
#include "core/scene/collider_tessellation.h"
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

// An analytic collider's tessellation as one surface: the copies of a vertex
// the renderer keeps for its shading (a box face's own corners, a sphere's
// seam and poles) merged, and the triangles that leaves with a repeated corner
// (at a pole) dropped. Copies agree to far below the 0.1 um they are matched at.
void merge_copies(const SurfaceMesh& mesh, std::vector<Vec3>& vertices,
                  std::vector<std::array<std::int32_t, 3>>& triangles) {
  std::map<std::array<long long, 3>, std::int32_t> seen;
  std::vector<std::int32_t> merged(mesh.vertex_count());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const Vec3 p = mesh.vertex(v);
    const std::array<long long, 3> key = {std::llround(p.x() * 1e7), std::llround(p.y() * 1e7),
                                          std::llround(p.z() * 1e7)};
    const auto [it, fresh] = seen.emplace(key, std::int32_t(vertices.size()));
    if (fresh) vertices.push_back(p);
    merged[v] = it->second;
  }
  for (std::size_t t = 0; t + 2 < mesh.index.size(); t += 3) {
    const std::array<std::int32_t, 3> tri = {merged[mesh.index[t]], merged[mesh.index[t + 1]],
                                             merged[mesh.index[t + 2]]};
    if (tri[0] != tri[1] && tri[1] != tri[2] && tri[2] != tri[0]) triangles.push_back(tri);
  }
}

// A mesh obstacle's vertices that some triangle uses, in the file's order.
void used_vertices(const ObstacleMesh& mesh, std::vector<Vec3>& vertices,
                   std::vector<std::int32_t>& source,
                   std::vector<std::array<std::int32_t, 3>>& triangles) {
  const TriangleSurface& surface = mesh.surface;
  std::vector<std::int32_t> index(surface.vertices.size(), -1);
  for (const auto& t : surface.triangles)
    for (const std::int32_t v : t)
      index[std::size_t(v)] = 0;
  for (std::size_t v = 0; v < index.size(); ++v)
    if (index[v] == 0) {
      index[v] = std::int32_t(source.size());
      source.push_back(std::int32_t(v));
      vertices.push_back(surface.vertices[v]);
    }
  for (const auto& t : surface.triangles)
    triangles.push_back(
        {index[std::size_t(t[0])], index[std::size_t(t[1])], index[std::size_t(t[2])]});
}

void write_obstacle_obj(const std::string& path, const std::string& comment,
                        const std::vector<Vec3>& vertices,
                        const std::vector<std::array<std::int32_t, 3>>& triangles) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# " << comment << "\n";
    char line[128];
    // %.9g: a float's every digit, what the point cache holds.
    for (const Vec3& p : vertices)
      out.write(line, std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x(), p.y(), p.z()));
    for (const auto& t : triangles)
      out.write(line,
                std::snprintf(line, sizeof line, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1));
  });
}

}  // namespace

std::string obstacle_path(const std::string& pc2_path, std::size_t k, const char* extension) {
  return pc2_path.substr(0, pc2_path.size() - 4) + ".obstacle" + std::to_string(k) + extension;
}

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
  for (const ModuleDeclaration& m : scene.modules)
    if (const auto* mesh = std::get_if<MeshSpec>(&m.spec); mesh && mesh->mesh) {
      files.push_back(mesh->mesh->obj_path);
      files.push_back(mesh->mesh->cache_path);
    }
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
  if (o.export_pc2) {
    mesh_path_ = pc2_mesh_path(*o.export_pc2);
    add_obstacles(*o.export_pc2);
  }
  // Two outputs at one path would leave only the one written last.
  std::vector<std::string> paths = {o.out, o.record.value_or(""), o.export_pc2.value_or(""),
                                    mesh_path_};
  for (const Obstacle& ob : obstacles_) {
    paths.push_back(ob.obj_path);
    paths.push_back(ob.pc2_path);
  }
  for (std::size_t i = 0; i < paths.size(); ++i)
    for (std::size_t j = i + 1; j < paths.size(); ++j)
      if (!paths[i].empty() && !paths[j].empty() && same_file(paths[i], paths[j]))
        throw InputError("command line", option,
                         "'" + paths[i] + "' is named for two outputs; give each its own file");
  const std::vector<std::string> inputs = input_files(scene);
  check_output_path("--record", o.record.value_or(""), inputs);
  check_output_path("--export-pc2", o.export_pc2.value_or(""), inputs);
  check_output_path("--export-pc2", mesh_path_, inputs);
  for (const Obstacle& ob : obstacles_) {
    check_output_path("--export-pc2", ob.obj_path, inputs);
    check_output_path("--export-pc2", ob.pc2_path, inputs);
  }
  if (o.record) recording_.emplace(*o.record, RecordingInfo{scene.name, nodes, fps_});
  if (o.export_pc2) pc2_.emplace(*o.export_pc2, nodes);
  for (Obstacle& ob : obstacles_)
    if (!ob.pc2_path.empty()) ob.pc2 = std::make_unique<Pc2Writer>(ob.pc2_path, ob.shape.size());
  positions_.resize(nodes);
}

void MotionOutputs::add_obstacles(const std::string& pc2_path) {
  // A plane's square: around the cloth as it starts, twice its size and at
  // least a metre either way.
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  for (const Vec3& p : scene_.topology.rest_positions) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const bool empty = scene_.topology.rest_positions.empty();
  const Vec3 centre = empty ? Vec3(Vec3::Zero()) : Vec3(0.5 * (lo + hi));
  const double half = std::max(1.0, empty ? 0.0 : 2 * (hi - lo).maxCoeff());
  std::size_t k = 0;
  for (std::size_t m = 0; m < scene_.modules.size(); ++m) {
    const ModuleSpec& spec = scene_.modules[m].spec;
    if (!is_collider(spec)) continue;
    Obstacle ob;
    ob.module = m;
    ob.type = scene_.modules[m].type;
    ob.obj_path = obstacle_path(pc2_path, ++k, ".obj");
    if (collider_moves(spec)) ob.pc2_path = obstacle_path(pc2_path, k, ".pc2");
    if (const auto* mesh = std::get_if<MeshSpec>(&spec)) {
      if (!mesh->mesh) throw std::logic_error("a mesh obstacle without its mesh");
      used_vertices(*mesh->mesh, ob.shape, ob.source, ob.triangles);
    } else {
      SurfaceMesh tessellated;
      append_collider(spec, centre, half, tessellated);
      merge_copies(tessellated, ob.shape, ob.triangles);
    }
    obstacles_.push_back(std::move(ob));
  }
}

void MotionOutputs::place(const Obstacle& ob, double t, std::vector<Vec3>& out) {
  const ModuleSpec& spec = scene_.modules[ob.module].spec;
  const RigidPose pose = collider_pose(spec, t);
  out.resize(ob.shape.size());
  const auto* mesh = std::get_if<MeshSpec>(&spec);
  if (mesh && mesh->mesh->deforms()) {
    obstacle_vertices_at(*mesh->mesh, t, deformed_);
    for (std::size_t k = 0; k < out.size(); ++k)
      out[k] = pose.apply(deformed_[std::size_t(ob.source[k])]);
  } else {
    for (std::size_t k = 0; k < out.size(); ++k)
      out[k] = pose.apply(ob.shape[k]);
  }
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
  for (Obstacle& ob : obstacles_)
    if (ob.pc2) {
      place(ob, t, placed_);
      ob.pc2->add_frame(placed_);
    }
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
  for (Obstacle& ob : obstacles_)
    if (ob.pc2) ob.pc2->keep_first(keep);
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
  const double start = times_.empty() ? 0.0 : times_.front();
  std::size_t k = 0;
  for (Obstacle& ob : obstacles_) {
    ++k;
    place(ob, start, placed_);
    write_obstacle_obj(ob.obj_path,
                       "obstacle " + std::to_string(k) + " of " + scene_.name + " (" + ob.type +
                           ", module " + std::to_string(ob.module) +
                           ") at t = " + show_number(start) + " s, metres, Y up" +
                           (ob.pc2 ? "; its point cache: " + ob.pc2_path : ""),
                       placed_, ob.triangles);
    std::string line = "exported obstacle " + std::to_string(k) + " (" + ob.type +
                       "): " + ob.obj_path + ", " + std::to_string(ob.shape.size()) + " vertices";
    if (ob.pc2) {
      ob.pc2->finish();
      line += ", and " + ob.pc2_path + " (it moves: its vertices at the same frames)";
    }
    lines.push_back(line);
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
  if (!obstacles_.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const Obstacle& ob : obstacles_) {
      nlohmann::json one = {{"type", ob.type},
                            {"module", ob.module},
                            {"obj", ob.obj_path},
                            {"vertices", ob.shape.size()}};
      if (ob.pc2) one["pc2"] = ob.pc2_path;
      list.push_back(one);
    }
    j["obstacles"] = list;
  }
  return j;
}

}  // namespace neurocloth
