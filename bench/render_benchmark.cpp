// Google Benchmark: one 1280x720 headless frame (draw and read back, as the
// snapshot command does) of the default scene's cloth resized to N x N, after
// 0.4 s of simulation (on the table, starting to drape). OSMesa's llvmpipe on
// the CPU. The same camera every frame, so from the second frame on the still
// part is copied, as in a window whose camera rests; BM_SnapshotFrameWhole
// draws every frame whole. Run with --benchmark_repetitions=9
// --benchmark_report_aggregates_only=true and quote the medians (docs/rendering.md).
#include <benchmark/benchmark.h>

#include "core/scene/frame_snapshot.h"
#include "core/scene/scene.h"
#include "render/osmesa_context.h"
#include "render/renderer.h"
#include "render/snapshot_framing.h"

namespace neurocloth {
namespace {

constexpr int kWidth = 1280, kHeight = 720;

FrameSnapshot draped(int n) {
  const Scene scene = resized_grid(load_scene(assets_directory() + "/scenes/table_drape.json"), n);
  Simulation sim = scene.make_simulation();
  sim.advance(0.4);
  FrameSnapshot s;
  s.geometry = make_geometry(scene);
  capture(sim, s);
  return s;
}

void frame(benchmark::State& st, const RenderOptions& options, bool copy = true) {
  const int n = static_cast<int>(st.range(0));
  const FrameSnapshot snapshot = draped(n);
  OsmesaContext context(kWidth, kHeight);
  Renderer renderer;
  renderer.set_background_cache(copy);
  const OrbitCamera camera = framing_camera(snapshot, double(kWidth) / kHeight);
  for (auto _ : st) {
    renderer.draw(snapshot, camera, options, kWidth, kHeight);
    benchmark::DoNotOptimize(renderer.read_pixels(kWidth, kHeight));
  }
  st.counters["triangles"] = static_cast<double>(snapshot.geometry->triangles.size());
}

void BM_SnapshotFrame(benchmark::State& st) {
  frame(st, RenderOptions());
}

// The same with every frame drawn whole, as while the camera moves: the clear,
// the table and the grid are not copied from the frame before (background_cache.h).
void BM_SnapshotFrameWhole(benchmark::State& st) {
  frame(st, RenderOptions(), false);
}

// Everything on: strain map with legend, wireframe, springs, nodes.
void BM_SnapshotFrameAllOverlays(benchmark::State& st) {
  RenderOptions o;
  o.strain = o.wireframe = o.springs = o.nodes = true;
  frame(st, o);
}

// llvmpipe rasterises on its own threads, so the calling thread's CPU time
// says little: the time quoted is wall time per frame.
BENCHMARK(BM_SnapshotFrame)
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SnapshotFrameWhole)
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_SnapshotFrameAllOverlays)
    ->Arg(32)
    ->Arg(64)
    ->Arg(128)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace neurocloth

BENCHMARK_MAIN();
