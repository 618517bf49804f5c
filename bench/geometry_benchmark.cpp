// Google Benchmark: what a mesh obstacle's questions cost, one query per
// iteration (core/geometry/triangle_bvh.h), on an icosphere of radius 1 with
// 4^k * 20 triangles (k = 5: 20,480, the obstacle issue 43 sizes for; k = 3:
// 1,280, where every triangle is also tried in turn for comparison):
//  - Nearest: the nearest point within 0.1 of a point at most 0.05 from the
//    sphere, inside or out (about two triangles' widths at k = 5);
//    NearestInContact: within 0.01 of a point at most 0.005 from it (a node
//    within a contact's thickness); NearestFar: within 0.1 of a point 0.5
//    away (a cloth nowhere near, found to be so);
//  - FirstHit: a node's step, a segment of length 0.02 from such a point;
//  - Build and Refit of the whole tree (a deforming obstacle refits each step).
// Quote medians of
//   --benchmark_repetitions=9 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <map>
#include <memory>
#include <random>
#include <vector>

#include "core/geometry/triangle_bvh.h"
#include "support/triangle_meshes.h"

namespace neurocloth {
namespace {

constexpr int kQueries = 4096;

struct Setup {
  TriangleSurface surface;
  TriangleBvh bvh;
  std::vector<Vec3> near_points, contact_points, far_points, step_ends;
};

// Built once per size: the sphere, its tree, and the queries' points.
const Setup& setup(int subdivisions) {
  static std::map<int, std::unique_ptr<Setup>> made;
  std::unique_ptr<Setup>& s = made[subdivisions];
  if (s) return *s;
  s = std::make_unique<Setup>();
  s->surface = test::icosphere(subdivisions);
  s->bvh.build(s->surface);
  std::mt19937 rng(1);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> off(-0.05, 0.05), touch(-0.005, 0.005);
  auto direction = [&] { return Vec3(g(rng), g(rng), g(rng)).normalized(); };
  for (int q = 0; q < kQueries; ++q) {
    const Vec3 p = (1 + off(rng)) * direction();
    s->near_points.push_back(p);
    s->step_ends.push_back(p + 0.02 * direction());
    s->contact_points.push_back((1 + touch(rng)) * direction());
    s->far_points.push_back((q % 2 ? 1.5 : 0.5) * direction());
  }
  return *s;
}

void BM_Nearest(benchmark::State& st) {
  const Setup& s = setup(static_cast<int>(st.range(0)));
  std::size_t q = 0;
  NearestHit hit;
  for (auto _ : st) {
    benchmark::DoNotOptimize(s.bvh.nearest(s.surface, s.near_points[q], 0.1, hit));
    q = (q + 1) % kQueries;
  }
}
BENCHMARK(BM_Nearest)->Arg(5)->Arg(3);

void BM_NearestInContact(benchmark::State& st) {
  const Setup& s = setup(static_cast<int>(st.range(0)));
  std::size_t q = 0;
  NearestHit hit;
  for (auto _ : st) {
    benchmark::DoNotOptimize(s.bvh.nearest(s.surface, s.contact_points[q], 0.01, hit));
    q = (q + 1) % kQueries;
  }
}
BENCHMARK(BM_NearestInContact)->Arg(5);

void BM_NearestFar(benchmark::State& st) {
  const Setup& s = setup(static_cast<int>(st.range(0)));
  std::size_t q = 0;
  NearestHit hit;
  for (auto _ : st) {
    benchmark::DoNotOptimize(s.bvh.nearest(s.surface, s.far_points[q], 0.1, hit));
    q = (q + 1) % kQueries;
  }
}
BENCHMARK(BM_NearestFar)->Arg(5);

void BM_NearestBruteForce(benchmark::State& st) {
  const Setup& s = setup(static_cast<int>(st.range(0)));
  std::size_t q = 0;
  NearestHit hit;
  for (auto _ : st) {
    benchmark::DoNotOptimize(nearest_brute_force(s.surface, s.near_points[q], 0.1, hit));
    q = (q + 1) % kQueries;
  }
}
BENCHMARK(BM_NearestBruteForce)->Arg(3);

void BM_FirstHit(benchmark::State& st) {
  const Setup& s = setup(static_cast<int>(st.range(0)));
  std::size_t q = 0;
  SegmentHit hit;
  for (auto _ : st) {
    benchmark::DoNotOptimize(s.bvh.first_hit(s.surface, s.near_points[q], s.step_ends[q], hit));
    q = (q + 1) % kQueries;
  }
}
BENCHMARK(BM_FirstHit)->Arg(5)->Arg(3);

void BM_FirstHitBruteForce(benchmark::State& st) {
  const Setup& s = setup(static_cast<int>(st.range(0)));
  std::size_t q = 0;
  SegmentHit hit;
  for (auto _ : st) {
    benchmark::DoNotOptimize(
        first_hit_brute_force(s.surface, s.near_points[q], s.step_ends[q], hit));
    q = (q + 1) % kQueries;
  }
}
BENCHMARK(BM_FirstHitBruteForce)->Arg(3);

void BM_Build(benchmark::State& st) {
  const Setup& s = setup(static_cast<int>(st.range(0)));
  TriangleBvh bvh;
  for (auto _ : st)
    bvh.build(s.surface);
}
BENCHMARK(BM_Build)->Arg(5)->Unit(benchmark::kMicrosecond);

void BM_Refit(benchmark::State& st) {
  const Setup& s = setup(static_cast<int>(st.range(0)));
  TriangleBvh bvh = s.bvh;
  for (auto _ : st)
    bvh.refit(s.surface);
}
BENCHMARK(BM_Refit)->Arg(5)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
