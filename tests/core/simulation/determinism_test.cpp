// Determinism against stored values: every shipped scene, with its own solver
// settings (the adaptive propagation where it declares it) and under every
// integrator at a step where that integrator is stable, run over a horizon in
// which its modules act, hashes to what tests/data/determinism_hashes.json
// holds, once through each spring kernel (their last bits differ:
// spring_kernel.h). Two runs compared within one process would agree however a
// change moved the numbers; a stored hash fails on any change to the bits, so a
// change to the numerics is made on purpose: rerun with
// NEUROCLOTH_UPDATE_HASHES=1, which rewrites the file, and commit the diff with
// the reason (docs/testing.md). A hashed run must end ok: a divergence rolls
// back to the last good state, which would hash the same for every integrator
// that diverged; the rollback has its own test below.
//
// The portable kernel's hashes are checked on any x86-64 CPU, the avx512
// kernel's where the CPU has AVX-512 F and VL (elsewhere they skip, saying
// so). They do not depend on the instruction set a build targets: the avx512
// hashes stored by a -march=native build (AVX-512, AMD Zen) were the default
// x86-64 build's to the bit, every scene and integrator (docs/testing.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <tuple>
#include <vector>

#include "core/io/text_file.h"
#include "core/network/spring_kernel.h"
#include "core/scene/scene.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {

// Simulated time per scene: long enough that each of its modules has acted
// (DeterminismHorizon.EachModuleActsWithinIt checks it), short enough that
// all cases run in seconds under the sanitizers. Every shipped scene must be
// listed: a new scene needs a horizon chosen for what it does.
const std::map<std::string, double> kHorizons = {
    {"cantilever.json", 0.05},             // the strip bends from the start (bending, air_drag)
    {"chain.json", 0.3},                   // the springs stretch and swing
    {"curtain.json", 0.6},                 // its pins start moving at 0.5 s
    {"drape_tester.json", 0.004},          // its rim ring rests on the support from the start
    {"flag.json", 0.4},                    // the wind and its gusts
    {"free_cloth.json", 0.3},              // no modules
    {"free_fall.json", 0.3},               // no modules
    {"hanging.json", 0.3},                 // no modules
    {"hanging_fuzzy.json", 0.3},           // no modules
    {"mannequin_drape.json", 0.6},         // on the head by 0.3 s; its folds touch by 0.5 s
    {"mesh_square.json", 0.3},             // no modules
    {"moving_obstacle.json", 1.3},         // on the tray at 0.1 s; carried from 1 s
    {"sphere_drop.json", 0.8},             // on the sphere at 0.29 s; folds touch later
    {"sphere_drop_mesh.json", 0.8},        // the same, over its mesh
    {"spring_mass.json", 0.3},             // no modules
    {"table_drape.json", 0.5},             // on the table at 0.23 s, then slides
    {"table_drape_damping003.json", 0.5},  // the same
    {"table_drape_damping005.json", 0.5},  // the same
    {"table_drape_dt001.json", 0.5},       // the same
    {"table_drape_mesh.json", 0.5},        // the same, over its mesh
};

const std::string kHashFile = std::string(NEUROCLOTH_TEST_DATA) + "/determinism_hashes.json";
// The hash key of a scene run with its own solver settings.
const std::string kOwnSettings = "own settings";

double horizon(const std::string& file) {
  const auto it = kHorizons.find(file);
  if (it == kHorizons.end())
    throw std::runtime_error(file + " has no horizon in determinism_test.cpp: give it one");
  return it->second;
}

// `shipped` under `integrator` at the scene's dt, taken in equal substeps
// under the integrator's stable step (SolverSettings::substep_above_cap): the
// implicit integrators and the stable explicit cases take dt itself.
Scene stable_fixed_step(const Scene& shipped, IntegratorKind integrator) {
  Scene scene = shipped;
  scene.solver.integrator = integrator;
  scene.solver.adaptive = false;
  scene.solver.substep_above_cap = true;
  return scene;
}

// The bits of the positions, velocities, time and step count after `seconds`.
std::uint64_t run_hash(const Scene& scene, double seconds, const std::string& what) {
  Simulation sim = scene.make_simulation();
  const RunStatus status = sim.advance(seconds);
  EXPECT_EQ(status, RunStatus::ok) << what << " diverged (" << sim.divergence_reason()
                                   << "): a diverging case is not a determinism hash";
  test::Fnv1a h;
  h.mix(sim.state());
  h.mix(sim.time());
  h.mix(static_cast<std::uint64_t>(sim.steps()));
  return h.hash;
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// Kernel -> scene file name -> its own settings or an integrator -> hash, in
// a stable order.
using Hashes = std::map<std::string, std::map<std::string, std::map<std::string, std::string>>>;

// One scene's hashes through `kernel`: its own settings and every integrator.
std::map<std::string, std::string> measure_scene(const std::string& name, SpringKernel kernel) {
  const std::string file = name + ".json";
  Scene scene = test::asset_scene(name);
  scene.solver.kernel = kernel;
  const double T = horizon(file);
  std::map<std::string, std::string> hashes;
  hashes[kOwnSettings] = hex(run_hash(scene, T, file + " with its own settings"));
  for (IntegratorKind k : kAllIntegrators)
    hashes[to_string(k)] =
        hex(run_hash(stable_fixed_step(scene, k), T, file + " under " + to_string(k)));
  return hashes;
}

bool updating() {
  const char* v = std::getenv("NEUROCLOTH_UPDATE_HASHES");
  return v != nullptr && std::string(v) == "1";
}

Hashes stored_hashes() {
  return nlohmann::json::parse(read_text_file(kHashFile, "hash file", kMaxSceneBytes))
      .get<Hashes>();
}

// One test per kernel and scene, so that ctest runs them side by side.
// Updating rewrites that entry of the file: run the binary itself for that
// (one process, the cases one after another), not ctest.
using KernelAndScene = std::tuple<SpringKernel, std::string>;
class Determinism : public ::testing::TestWithParam<KernelAndScene> {};

TEST_P(Determinism, TheSceneMatchesItsStoredHashes) {
  const auto& [kernel, name] = GetParam();
  if (const std::string missing = kernel_unavailable(kernel); !missing.empty())
    GTEST_SKIP() << missing << "; its stored hashes are checked on a CPU that has it";
  const std::string file = name + ".json";
  const std::map<std::string, std::string> measured = measure_scene(name, kernel);
  if (updating()) {
    Hashes all = stored_hashes();
    all[to_string(kernel)][file] = measured;
    write_file_atomically(kHashFile, nlohmann::json(all).dump(2) + "\n");
    std::printf(
        "wrote %s for %s through the %s kernel: review the diff and commit it with the "
        "reason\n",
        kHashFile.c_str(), file.c_str(), to_string(kernel));
    return;
  }
  const Hashes stored = stored_hashes();
  const std::string how =
      "\n  (an intended change to the numerics: rerun core_tests with "
      "NEUROCLOTH_UPDATE_HASHES=1, review and commit " +
      kHashFile + "; docs/testing.md)";
  const std::string what = file + " through the " + to_string(kernel) + " kernel";
  const auto k = stored.find(to_string(kernel));
  ASSERT_NE(k, stored.end()) << "no stored hashes for the " << to_string(kernel) << " kernel"
                             << how;
  const auto s = k->second.find(file);
  ASSERT_NE(s, k->second.end()) << what << " has no stored hashes" << how;
  for (const auto& [run, hash] : measured) {
    const bool known = s->second.count(run) != 0;
    EXPECT_TRUE(known) << what << " (" << run << ") has no stored hash" << how;
    if (known) {
      EXPECT_EQ(hash, s->second.at(run)) << what << " (" << run << ") ran to other bits" << how;
    }
  }
  EXPECT_EQ(s->second.size(), measured.size()) << what << ": stored cases no longer run" << how;
}

std::string case_name(const ::testing::TestParamInfo<KernelAndScene>& info) {
  return std::string(to_string(std::get<0>(info.param))) + "_" + std::get<1>(info.param);
}

INSTANTIATE_TEST_SUITE_P(EveryShippedScene, Determinism,
                         ::testing::Combine(::testing::Values(SpringKernel::portable,
                                                              SpringKernel::avx512),
                                            ::testing::ValuesIn(test::shipped_scene_names())),
                         case_name);

// The two kernels' hashes differ wherever the kernel evaluates springs: the
// network's own step, the explicit ones and implicit Euler's forces. (The
// projective and VBD steps form their springs' terms themselves, and
// free_fall has no springs: those run to the same bits through either.) Equal
// hashes elsewhere would mean one kernel never ran.
TEST(DeterminismFile, TheKernelsHashesDifferWhereTheKernelRuns) {
  const Hashes stored = stored_hashes();
  ASSERT_EQ(stored.count("portable"), 1u);
  ASSERT_EQ(stored.count("avx512"), 1u);
  int checked = 0;
  for (const auto& [file, runs] : stored.at("portable")) {
    if (file == "free_fall.json") continue;
    for (const auto& [run, hash] : runs) {
      if (run == to_string(IntegratorKind::projective) || run == to_string(IntegratorKind::vbd))
        continue;
      ++checked;
      EXPECT_NE(stored.at("avx512").at(file).at(run), hash) << file << " (" << run << ")";
    }
  }
  EXPECT_GE(checked, 13 * 6);
}

// Every stored scene is still shipped (and so still checked).
TEST(DeterminismFile, HoldsOnlyShippedScenes) {
  const std::vector<std::string> names = test::shipped_scene_names();
  ASSERT_GE(names.size(), 6u);  // or the directory was not read
  for (const auto& [kernel, scenes] : stored_hashes())
    for (const auto& [file, unused] : scenes)
      EXPECT_NE(std::find(names.begin(), names.end(), file.substr(0, file.size() - 5)), names.end())
          << file << " is stored (" << kernel << ") but no longer shipped";
}

// The horizon is where the modules act: without any one of them the scene's
// own run ends elsewhere. (A module that has not touched the cloth by then
// would leave the bits as they are, and its code would go unhashed.)
TEST(DeterminismHorizon, EachModuleActsWithinIt) {
  for (const std::string& name : test::shipped_scene_names()) {
    const std::string file = name + ".json";
    const Scene scene = test::asset_scene(name);
    if (scene.modules.empty()) continue;
    const double T = horizon(file);
    const std::uint64_t all = run_hash(scene, T, file);
    for (std::size_t m = 0; m < scene.modules.size(); ++m) {
      Scene without = scene;
      without.modules.erase(without.modules.begin() + static_cast<std::ptrdiff_t>(m));
      EXPECT_NE(run_hash(without, T, file + " without " + scene.modules[m].type), all)
          << file << ": " << scene.modules[m].type << " has not acted by t = " << T << " s";
    }
  }
}

// A run that diverges rolls back to its last good state: that state is the
// one the same run reaches at the reported time, bit for bit, and the status
// stays diverged. The flag's wind at its scene's dt of 0.01 s, as a plain
// fixed step, is far above the explicit integrators' stable step (they used to
// store one hash between them: the start they rolled back to); checked after
// every step, the last good state is one the run reached, not the start.
TEST(DeterminismRollback, ADivergedRunKeepsTheBitsOfItsLastGoodState) {
  const Scene flag = test::asset_scene("flag");
  for (IntegratorKind k : {IntegratorKind::network, IntegratorKind::explicit_euler,
                           IntegratorKind::verlet, IntegratorKind::rk4}) {
    Scene scene = flag;
    scene.solver.integrator = k;
    scene.solver.adaptive = false;
    scene.solver.divergence.check_interval = 1;
    Simulation sim = scene.make_simulation();
    ASSERT_EQ(sim.advance(2.0), RunStatus::diverged) << to_string(k);
    EXPECT_FALSE(sim.divergence_reason().empty());
    EXPECT_GT(sim.steps(), 0) << to_string(k);
    EXPECT_TRUE(sim.state().all_finite());
    Simulation replay = scene.make_simulation();
    ASSERT_EQ(replay.advance(sim.time()), RunStatus::ok) << to_string(k);
    EXPECT_EQ(replay.steps(), sim.steps()) << to_string(k);
    EXPECT_EQ(test::state_hash(replay.state()), test::state_hash(sim.state())) << to_string(k);
  }
}

}  // namespace
}  // namespace neurocloth
