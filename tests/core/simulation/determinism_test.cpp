// Determinism against stored values: every shipped scene under every
// integrator, run a short fixed time, hashes to what
// tests/data/determinism_hashes.json holds. Two runs compared within one
// process would agree however a change moved the numbers; a stored hash fails
// on any change to the bits, so a change to the numerics is made on purpose:
// rerun with NEUROCLOTH_UPDATE_HASHES=1, which rewrites the file, and commit
// the diff with the reason (docs/testing.md).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "core/io/text_file.h"
#include "core/network/spring_kernel.h"
#include "core/scene/scene.h"
#include "support/test_support.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;

// Simulated time per case: enough steps for every scene's forces and modules
// to act (and for the stiffer cases to diverge, which is hashed like the rest),
// short enough that all cases run in seconds under the sanitizers.
constexpr double kSeconds = 0.2;

const std::string kHashFile = std::string(NEUROCLOTH_TEST_DATA) + "/determinism_hashes.json";

// The scene's dt as a fixed step under `integrator`, run kSeconds: the bits of
// the positions, velocities, time, step count and status.
std::uint64_t run_hash(const Scene& shipped, IntegratorKind integrator) {
  Scene scene = shipped;
  scene.solver.integrator = integrator;
  scene.solver.adaptive = false;
  Simulation sim = scene.make_simulation();
  const RunStatus status = sim.advance(kSeconds);
  test::Fnv1a h;
  h.mix(sim.state());
  h.mix(sim.time());
  h.mix(static_cast<std::uint64_t>(sim.steps()));
  h.mix(static_cast<std::uint64_t>(status));
  return h.hash;
}

std::string hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// Scene file name -> integrator -> hash, in a stable order.
using Hashes = std::map<std::string, std::map<std::string, std::string>>;

Hashes measure_every_case() {
  Hashes hashes;
  for (const auto& entry : fs::directory_iterator(fs::path(assets_directory()) / "scenes")) {
    if (entry.path().extension() != ".json") continue;
    const Scene scene = load_scene(entry.path().string());
    for (IntegratorKind k : kAllIntegrators)
      hashes[entry.path().filename().string()][to_string(k)] = hex(run_hash(scene, k));
  }
  return hashes;
}

bool updating() {
  const char* v = std::getenv("NEUROCLOTH_UPDATE_HASHES");
  return v != nullptr && std::string(v) == "1";
}

TEST(Determinism, EveryShippedSceneUnderEveryIntegratorMatchesItsStoredHash) {
  // The stored bits are an AVX-512 build's: its spring kernel's 1/len differs
  // from the portable one's in the last place (spring_kernel.h).
  if (!avx512_kernel_compiled())
    GTEST_SKIP() << "the stored hashes are an AVX-512 build's; this build uses the portable "
                    "spring kernel (docs/network.md, \"Why the step is fast\")";
  const Hashes measured = measure_every_case();
  // Every scene and integrator, or the directory was not read.
  ASSERT_GE(measured.size(), 6u);
  if (updating()) {
    write_file_atomically(kHashFile, nlohmann::json(measured).dump(2) + "\n");
    std::printf("wrote %s: review the diff and commit it with the reason\n", kHashFile.c_str());
    return;
  }
  const Hashes stored =
      nlohmann::json::parse(read_text_file(kHashFile, "hash file", kMaxSceneBytes)).get<Hashes>();
  const std::string how =
      "\n  (an intended change to the numerics: rerun with "
      "NEUROCLOTH_UPDATE_HASHES=1, review and commit " +
      kHashFile + "; docs/testing.md)";
  for (const auto& [scene, by_integrator] : measured)
    for (const auto& [integrator, hash] : by_integrator) {
      const auto s = stored.find(scene);
      const bool known = s != stored.end() && s->second.count(integrator) != 0;
      EXPECT_TRUE(known) << scene << " under " << integrator << " has no stored hash" << how;
      if (known) {
        EXPECT_EQ(hash, s->second.at(integrator))
            << scene << " under " << integrator << " ran to other bits" << how;
      }
    }
  for (const auto& [scene, unused] : stored)
    EXPECT_EQ(measured.count(scene), 1u) << scene << " is stored but no longer shipped" << how;
}

}  // namespace
}  // namespace neurocloth
