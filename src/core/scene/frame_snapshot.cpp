#include "core/scene/frame_snapshot.h"

#include <type_traits>

#include "core/modules/collider_motion.h"
#include "core/scene/scene.h"

namespace neurocloth {

std::shared_ptr<const SceneGeometry> make_geometry(const Scene& scene) {
  auto g = std::make_shared<SceneGeometry>();
  g->scene_name = scene.name;
  g->triangles = scene.topology.triangles;
  if (scene.grid && (scene.grid->rows > kCoarseGridFrom || scene.grid->cols > kCoarseGridFrom)) {
    auto every_other = [](int count) {
      std::vector<int> kept;
      for (int k = 0; k < count; k += 2)
        kept.push_back(k);
      if (kept.back() != count - 1) kept.push_back(count - 1);
      return kept;
    };
    const std::vector<int> rows = every_other(scene.grid->rows);
    const std::vector<int> cols = every_other(scene.grid->cols);
    const NodeNumbering& numbering = scene.topology.numbering;
    auto node = [&](int r, int c) {
      return std::int32_t(numbering.node(r * scene.grid->cols + c));
    };
    // Wound as grid_builder's triangles are.
    for (std::size_t r = 0; r + 1 < rows.size(); ++r)
      for (std::size_t c = 0; c + 1 < cols.size(); ++c) {
        const std::int32_t a = node(rows[r], cols[c]), b = node(rows[r], cols[c + 1]);
        const std::int32_t d = node(rows[r + 1], cols[c]), e = node(rows[r + 1], cols[c + 1]);
        g->coarse_triangles.push_back({a, d, b});
        g->coarse_triangles.push_back({b, d, e});
      }
  }
  g->node_count = scene.topology.rest_positions.size();
  g->numbering = scene.topology.numbering;
  for (const SpringSpec& s : scene.topology.springs) {
    g->spring_a.push_back(s.a);
    g->spring_b.push_back(s.b);
    g->spring_family.push_back(s.family);
    g->rest_length.push_back(static_cast<float>(
        (scene.topology.rest_positions[s.b] - scene.topology.rest_positions[s.a]).norm()));
  }
  for (const ModuleDeclaration& m : scene.modules)
    if (is_collider(m.spec)) g->colliders.push_back(m.spec);
  return g;
}

void capture(const Simulation& sim, FrameSnapshot& out) {
  const ClothState& s = sim.state();
  const std::size_t n = s.size();
  out.position.resize(3 * n);
  out.pinned.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    out.position[3 * i] = static_cast<float>(s.x[i]);
    out.position[3 * i + 1] = static_cast<float>(s.y[i]);
    out.position[3 * i + 2] = static_cast<float>(s.z[i]);
    out.pinned[i] = sim.network().masses.pinned(i) ? 1 : 0;
  }
  out.time = sim.time();
  place_colliders(out.geometry.get(), out.time, out.colliders);
}

void place_colliders(const SceneGeometry* geometry, double t,
                     std::vector<FrameSnapshot::ColliderPlacement>& out) {
  if (!geometry) {
    out.clear();
    return;
  }
  out.resize(geometry->colliders.size());
  // A deforming mesh's vertices in double, before they become the snapshot's
  // floats: kept per thread, so a frame allocates nothing once it has grown.
  thread_local std::vector<Vec3> deformed;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const ModuleSpec& spec = geometry->colliders[i];
    FrameSnapshot::ColliderPlacement& p = out[i];
    p.pose = collider_posed(spec) ? collider_pose(spec, t) : RigidPose{};
    const auto* mesh = std::get_if<MeshSpec>(&spec);
    if (!mesh || !mesh->mesh || !mesh->mesh->deforms()) {
      p.vertices.clear();
      continue;
    }
    obstacle_vertices_at(*mesh->mesh, t, deformed);
    p.vertices.resize(3 * deformed.size());
    for (std::size_t v = 0; v < deformed.size(); ++v)
      for (int d = 0; d < 3; ++d)
        p.vertices[3 * v + std::size_t(d)] = static_cast<float>(deformed[v][d]);
  }
}

}  // namespace neurocloth
