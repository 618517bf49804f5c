// The program on CPUs other than this one (docs/building.md, "Which CPU a
// build targets"): one binary for every x86-64, the AVX-512 kernel chosen at
// run time. What a CPU without AVX-512 runs is reproduced two ways: by masking
// the feature (NEUROCLOTH_DISABLE_CPU_FEATURES=avx512) and, where qemu's
// user-mode emulator is installed (.ci/packages), by running the very binary
// on an emulated baseline x86-64 CPU, which executes no AVX instruction at all
// and stops the program on the first one.
#include <cstdlib>

#include "core/base/cpu_features.h"
#include "core/network/spring_kernel.h"
#include "support/cli_fixture.h"

namespace neurocloth::cli_test {
namespace {

const std::string kMaskAvx512 = std::string(kDisableCpuFeaturesVariable) + "=avx512 ";

// The emulator, or "" where it is not installed.
std::string qemu() {
  return std::system("command -v qemu-x86_64 >/dev/null 2>&1") == 0 ? "qemu-x86_64" : "";
}

// The emulated CPU: qemu64 is plain x86-64 (SSE2, no AVX, no FMA).
const std::vector<std::string> kBaselineCpu = {"-cpu", "qemu64"};

TEST_F(Cli, AMaskedAvx512IsRefusedByNameAndAutoRunsPortable) {
  const Outcome bad =
      run({"bench", "--size", "8", "--steps", "5", "--repeat", "1", "--kernel", "avx512"}, 120,
          kMaskAvx512);
  EXPECT_EQ(bad.code, kInputError) << bad.err;
  EXPECT_NE(bad.err.find("--kernel"), std::string::npos) << bad.err;
  // Where the CPU has AVX-512 the refusal names the mask; elsewhere, the CPU.
  EXPECT_NE(bad.err.find(cpu_reports_avx512() ? kDisableCpuFeaturesVariable : "lacks them"),
            std::string::npos)
      << bad.err;
  const Outcome r =
      run({"bench", "--size", "8", "--steps", "5", "--repeat", "1", "--json"}, 120, kMaskAvx512);
  ASSERT_EQ(r.code, kOk) << r.err;
  const json doc = json::parse(r.out);
  EXPECT_EQ(doc.at("kernel"), "portable");
  EXPECT_EQ(doc.at("cpu_has_avx512"), false);
}

TEST_F(Cli, AnUnknownMaskedFeatureRunsNothing) {
  const Outcome r =
      run({"simulate", scene_asset("hanging"), "--seconds", "0.01", "--out", result_path()}, 120,
          std::string(kDisableCpuFeaturesVariable) + "=avx2,avx512 ");
  EXPECT_EQ(r.code, kUsage) << r.err;
  EXPECT_NE(r.err.find(kDisableCpuFeaturesVariable), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'avx2'"), std::string::npos) << r.err;
  EXPECT_TRUE(files_in_out_dir().empty());
}

// The binary on a CPU without AVX-512 (nor FMA) runs the portable kernel to
// the same bits as this CPU does when AVX-512 is masked; and refuses avx512 by
// name. The flag: springs, wind and gusts (a signal of the clock, portable_trig.h).
TEST_F(Cli, OnABaselineCpuTheBinaryRunsWhatTheMaskRuns) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  // Their runtimes' shadow memory does not run emulated (qemu kills the
  // program); the release build runs this test.
  GTEST_SKIP() << "a sanitizer build's program does not run under qemu";
#endif
  const std::string emulator = qemu();
  if (emulator.empty()) GTEST_SKIP() << "qemu-x86_64 is not installed (qemu-user, .ci/packages)";
  const std::vector<std::string> sim = {"simulate", scene_asset("flag"), "--seconds", "0.4",
                                        "--out"};
  std::vector<std::string> emulated = kBaselineCpu;
  emulated.push_back(NEUROCLOTH_CLI);
  for (const std::string& a : sim)
    emulated.push_back(a);
  emulated.push_back((out_dir() / "emulated.json").string());
  const Outcome e = test::run_process("", emulator, emulated, 600, dir_);
  ASSERT_EQ(e.code, kOk) << e.err;
  std::vector<std::string> masked = sim;
  masked.push_back((out_dir() / "masked.json").string());
  const Outcome m = run(masked, 120, kMaskAvx512);
  ASSERT_EQ(m.code, kOk) << m.err;
  const auto read = [&](const char* name) {
    std::ifstream in(out_dir() / name);
    return json::parse(in);
  };
  const json a = read("emulated.json"), b = read("masked.json");
  ASSERT_TRUE(a.contains("positions"));
  EXPECT_EQ(a.at("steps"), b.at("steps"));
  EXPECT_EQ(a.at("positions"), b.at("positions"));  // every double, to the bit (round-trip text)
  EXPECT_EQ(a.at("velocities"), b.at("velocities"));
  if (cpu_reports_avx512()) {  // and the mask did change the kernel here
    std::vector<std::string> native = sim;
    native.push_back((out_dir() / "native.json").string());
    ASSERT_EQ(run(native).code, kOk);
    EXPECT_NE(read("native.json").at("positions"), b.at("positions"));
  }

  std::vector<std::string> bench = kBaselineCpu;
  for (const std::string& arg :
       {std::string(NEUROCLOTH_CLI), std::string("bench"), std::string("--size"), std::string("4"),
        std::string("--steps"), std::string("2"), std::string("--repeat"), std::string("1"),
        std::string("--kernel"), std::string("avx512")})
    bench.push_back(arg);
  const Outcome refused = test::run_process("", emulator, bench, 600, dir_);
  EXPECT_EQ(refused.code, kInputError) << refused.err;
  EXPECT_NE(refused.err.find("lacks them"), std::string::npos) << refused.err;
}

}  // namespace
}  // namespace neurocloth::cli_test
