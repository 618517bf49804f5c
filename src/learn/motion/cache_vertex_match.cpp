#include "learn/motion/cache_vertex_match.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "core/geometry/point_tree.h"
#include "core/io/input_error.h"

namespace neurocloth {
namespace {

std::string metres(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.3g m", v);
  return s;
}

std::string shown_point(const Vec3& p) {
  char s[96];
  std::snprintf(s, sizeof s, "(%.6g, %.6g, %.6g)", p.x(), p.y(), p.z());
  return s;
}

// The diagonal of the positions' bounding box.
double size_of(const std::vector<Vec3>& points) {
  Vec3 lo = points.front(), hi = points.front();
  for (const Vec3& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

}  // namespace

std::vector<std::int32_t> mesh_nodes(const std::vector<Vec3>& mesh,
                                     const std::vector<Vec3>& scene_positions,
                                     const std::string& cache_path, const std::string& mesh_path,
                                     std::string& note) {
  if (mesh.size() != scene_positions.size() || mesh.empty())
    throw std::invalid_argument("mesh_nodes: a mesh of " + std::to_string(mesh.size()) +
                                " vertices for " + std::to_string(scene_positions.size()) +
                                " scene nodes");
  const double size = size_of(scene_positions);
  const double tolerance = kCacheMeshTolerance * size;
  double in_order = 0;
  for (std::size_t k = 0; k < mesh.size(); ++k)
    in_order = std::max(in_order, (mesh[k] - scene_positions[k]).norm());
  if (in_order <= tolerance) {
    note =
        "vertex k is node k (the mesh sits on the scene's nodes within " + metres(in_order) + ")";
    return {};
  }

  // Each vertex takes the closest scene node within the tolerance that no
  // vertex took before it: a few candidates cover nodes that coincide.
  const PointList points{&scene_positions};
  const PointTree tree(3, points, point_tree_leaves());
  constexpr std::size_t kCandidates = 8;
  const std::size_t wanted = std::min(kCandidates, scene_positions.size());
  const double tolerance2 = tolerance * tolerance;
  std::vector<std::int32_t> node_of(mesh.size(), -1), vertex_on(mesh.size(), -1);
  double farthest = 0;
  for (std::size_t k = 0; k < mesh.size(); ++k) {
    std::uint32_t index[kCandidates];
    double distance2[kCandidates];
    const std::size_t found = tree.knnSearch(mesh[k].data(), wanted, index, distance2);
    if (found == 0 || distance2[0] > tolerance2)
      throw InputError(cache_path, "--reference-mesh",
                       "not the scene's cloth: vertex " + std::to_string(k) + " of the mesh '" +
                           mesh_path + "' at " + shown_point(mesh[k]) + " is " +
                           metres(found ? std::sqrt(distance2[0]) : INFINITY) +
                           " from the nearest scene node, more than " + metres(tolerance) +
                           " (1e-4 of the cloth's size, " + metres(size) +
                           "); in order, vertex k is up to " + metres(in_order) + " from node k");
    std::size_t c = 0;
    while (c < found && distance2[c] <= tolerance2 && vertex_on[index[c]] >= 0)
      ++c;
    if (c == found || distance2[c] > tolerance2)
      throw InputError(cache_path, "--reference-mesh",
                       "not the scene's cloth: vertices " + std::to_string(vertex_on[index[0]]) +
                           " and " + std::to_string(k) + " of the mesh '" + mesh_path +
                           "' both sit on scene node " + std::to_string(index[0]) + " (within " +
                           metres(tolerance) + ")");
    node_of[k] = static_cast<std::int32_t>(index[c]);
    vertex_on[index[c]] = static_cast<std::int32_t>(k);
    farthest = std::max(farthest, std::sqrt(distance2[c]));
  }
  note =
      "vertices matched to the scene's nodes by position (the mesh numbers them its own way; "
      "each within " +
      metres(farthest) + ")";
  return node_of;
}

void match_cache_to_scene(ReferenceMotion& cache, const std::vector<Vec3>& mesh,
                          const std::string& mesh_path, std::size_t node_count,
                          const std::vector<Vec3>& scene_positions) {
  const std::size_t vertices = cache.frames.front().positions.size();
  check_cache_vertex_count(cache.path, vertices, mesh_path, mesh.size());
  if (vertices != node_count)
    throw InputError(cache.path, "vertex count",
                     "the cache and its mesh '" + mesh_path + "' have " + std::to_string(vertices) +
                         " vertices, the scene's cloth " + std::to_string(node_count) + " nodes");
  if (!scene_positions.empty() && scene_positions.size() != node_count)
    throw std::invalid_argument("match_cache_to_scene: " + std::to_string(scene_positions.size()) +
                                " scene positions for " + std::to_string(node_count) + " nodes");

  double as_written = 0, turned = 0;
  const bool z_up = cache_is_z_up(cache.frames.front().positions, mesh, as_written, turned);
  if (z_up)
    for (ReferenceFrame& frame : cache.frames)
      for (Vec3& p : frame.positions)
        p = z_up_to_y_up(p);
  const std::string axes =
      z_up ? "turned from Z-up to Y-up, (x, y, z) -> (x, z, -y): its first frame is " +
                 metres(turned) + " (rms) from the mesh so, " + metres(as_written) + " as written"
           : "read as written (Y-up): its first frame is " + metres(as_written) +
                 " (rms) from the mesh, " + metres(turned) + " turned from Z-up";

  std::string nodes = "vertex k taken as node k (no scene positions to check the mesh against)";
  if (!scene_positions.empty()) {
    const std::vector<std::int32_t> node_of =
        mesh_nodes(mesh, scene_positions, cache.path, mesh_path, nodes);
    if (!node_of.empty()) {
      std::vector<Vec3> moved(vertices);
      for (ReferenceFrame& frame : cache.frames) {
        for (std::size_t k = 0; k < vertices; ++k)
          moved[node_of[k]] = frame.positions[k];
        frame.positions.swap(moved);
      }
    }
  }
  cache.note = axes + "; " + nodes + (cache.note.empty() ? "" : "; " + cache.note);
}

}  // namespace neurocloth
