#include "core/scene/frame_snapshot.h"

#include <type_traits>

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
  for (const ModuleDeclaration& m : scene.modules) {
    std::visit(
        [&](const auto& spec) {
          using T = std::decay_t<decltype(spec)>;
          if constexpr (std::is_same_v<T, PlaneSpec> || std::is_same_v<T, BoxSpec> ||
                        std::is_same_v<T, SphereSpec> || std::is_same_v<T, CapsuleSpec>)
            g->colliders.push_back(spec);
        },
        m.spec);
  }
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
}

}  // namespace neurocloth
