// Google Benchmark: what scene modules cost on top of the bare network. The
// table drape's cloth resized to N x N is stepped by the one step benchmark's
// rule (step_bench.h: fixed network steps) five ways: bare (no modules), with
// a declared plane that no node ever reaches, lying on the table (the box
// collider in contact with the cloth's middle every step), lying on the same
// table as a mesh of 12 triangles and as one of 19,200 (each face 40 x 40
// squares), and with that fine mesh 100 m below (never reached). Quote medians of
//   --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <map>
#include <memory>

#include "app/cli/step_bench.h"
#include "core/geometry/triangle_surface.h"

namespace neurocloth {
namespace {

enum Variant {
  bare = 0,
  unreached_plane = 1,
  on_table = 2,
  on_mesh_table = 3,
  on_fine_mesh_table = 4,
  unreached_fine_mesh = 5
};

// The box as a mesh, each face `cells` x `cells` squares of two triangles.
MeshSpec box_mesh(const BoxSpec& box, int cells) {
  auto mesh = std::make_shared<ObstacleMesh>();
  TriangleSurface& s = mesh->surface;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto first = static_cast<std::int32_t>(s.vertices.size());
      for (int i = 0; i <= cells; ++i)
        for (int j = 0; j <= cells; ++j) {
          Vec3 p = box.center;
          p[axis] += side * box.half_extents[axis];
          p[u] += (2.0 * i / cells - 1.0) * box.half_extents[u];
          p[v] += (2.0 * j / cells - 1.0) * box.half_extents[v];
          s.vertices.push_back(p);
        }
      auto at = [&](int i, int j) { return first + std::int32_t(i * (cells + 1) + j); };
      for (int i = 0; i < cells; ++i)
        for (int j = 0; j < cells; ++j) {
          // Outward: u x v is +axis, so counter-clockwise seen from outside on the + side.
          if (side > 0) {
            s.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
            s.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
          } else {
            s.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
            s.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
          }
        }
    }
  // The faces' grids share their border vertices by position only: weld them.
  std::vector<std::int32_t> same(s.vertices.size());
  std::vector<Vec3> kept;
  std::map<std::array<long long, 3>, std::int32_t> index;
  for (std::size_t i = 0; i < s.vertices.size(); ++i) {
    const Vec3& p = s.vertices[i];
    const std::array<long long, 3> key = {std::llround(p.x() * 1e9), std::llround(p.y() * 1e9),
                                          std::llround(p.z() * 1e9)};
    const auto found = index.emplace(key, std::int32_t(kept.size()));
    if (found.second) kept.push_back(p);
    same[i] = found.first->second;
  }
  s.vertices = kept;
  for (auto& t : s.triangles)
    for (auto& c : t)
      c = same[std::size_t(c)];
  finish_surface(s);
  MeshSpec spec;
  spec.mesh = mesh;
  spec.contact = box.contact;
  return spec;
}

Scene variant_scene(Variant v, int n) {
  Scene scene = table_drape_cloth(n);
  const ModuleDeclaration table = scene.modules.at(0);  // the box
  scene.modules.clear();
  if (v == unreached_plane) {
    PlaneSpec far_below;
    far_below.point = Vec3(0, -100, 0);
    scene.modules.push_back({"plane", "{\"type\":\"plane\"}", far_below});
  }
  if (v == unreached_fine_mesh) {
    BoxSpec far_below = std::get<BoxSpec>(table.spec);
    far_below.center.y() -= 100;
    scene.modules.push_back({"mesh", "{\"type\":\"mesh\"}", box_mesh(far_below, 40)});
  }
  if (v == on_table || v == on_mesh_table || v == on_fine_mesh_table) {
    if (v == on_table)
      scene.modules.push_back(table);
    else
      scene.modules.push_back(
          {"mesh", "{\"type\":\"mesh\"}",
           box_mesh(std::get<BoxSpec>(table.spec), v == on_mesh_table ? 1 : 40)});
    // Lower the cloth onto the table top (0.75 m) so the middle is in contact.
    const double drop = scene.topology.rest_positions[0].y() - (0.75 + 0.004);
    for (Vec3& p : scene.topology.rest_positions)
      p.y() -= drop;
  }
  return scene;
}

void BM_Modules(benchmark::State& st) {
  const auto v = static_cast<Variant>(st.range(0));
  const int n = static_cast<int>(st.range(1));
  StepBench bench(variant_scene(v, n), IntegratorKind::network);
  long steps = 0;
  for (auto _ : st)
    steps += bench.run(StepBench::kFrameSteps);
  if (bench.simulation().status() != RunStatus::ok) st.SkipWithError("diverged");
  static const char* const names[] = {"bare",          "unreached_plane",    "on_table",
                                      "on_mesh_table", "on_fine_mesh_table", "unreached_fine_mesh"};
  st.SetLabel(names[v]);
  st.counters["us_per_step"] = benchmark::Counter(
      static_cast<double>(steps) * 1e-6, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

BENCHMARK(BM_Modules)
    ->ArgsProduct({{bare, unreached_plane, on_table, on_mesh_table, on_fine_mesh_table,
                    unreached_fine_mesh},
                   {32, 64, 128}})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
