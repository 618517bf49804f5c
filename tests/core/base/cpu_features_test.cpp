// The CPU as the program sees it at run time (cpu_features.h) and the kernel
// it therefore runs (spring_kernel.h).
#include "core/base/cpu_features.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "core/network/spring_kernel.h"

namespace neurocloth {
namespace {

// Sets the mask variable for one test and puts back what was there.
class MaskVariable {
 public:
  explicit MaskVariable(const std::string& value) {
    if (const char* v = std::getenv(kDisableCpuFeaturesVariable)) before_ = v;
    setenv(kDisableCpuFeaturesVariable, value.c_str(), 1);
  }
  ~MaskVariable() {
    if (before_)
      setenv(kDisableCpuFeaturesVariable, before_->c_str(), 1);
    else
      unsetenv(kDisableCpuFeaturesVariable);
  }

 private:
  std::optional<std::string> before_;
};

TEST(CpuFeatures, TheMaskTakesKnownNamesInAList) {
  for (const char* fine : {"", "avx512", " avx512 ", "avx512,avx512", ",avx512,"}) {
    MaskVariable mask(fine);
    EXPECT_EQ(disabled_cpu_features_error(), "") << "'" << fine << "'";
  }
}

TEST(CpuFeatures, AnUnknownNameOrAnOverlongValueIsNamed) {
  {
    MaskVariable mask("avx512,AVX2");
    const std::string e = disabled_cpu_features_error();
    EXPECT_NE(e.find(kDisableCpuFeaturesVariable), std::string::npos) << e;
    EXPECT_NE(e.find("'AVX2'"), std::string::npos) << e;
  }
  {
    MaskVariable mask(std::string(100000, 'a'));
    const std::string e = disabled_cpu_features_error();
    EXPECT_NE(e.find("100000 characters"), std::string::npos) << e;
  }
}

// The kernel may run exactly where the CPU has AVX-512 and it is not masked
// (which kernel automatic then picks: spring_kernel_test.cpp).
TEST(CpuFeatures, TheAvx512KernelRunsExactlyWhereTheCpuHasIt) {
  EXPECT_EQ(avx512_kernel_available(), cpu_has_avx512());
  EXPECT_LE(cpu_has_avx512(), cpu_reports_avx512());
}

// Run by ctest's core_tests_on_a_baseline_cpu under qemu's plain x86-64
// (tests/CMakeLists.txt), which sets NEUROCLOTH_EXPECT_CPU=baseline: the
// emulated CPU must read as one without AVX-512, or the run there proves
// nothing about such a CPU.
TEST(CpuFeatures, AnEmulatedBaselineCpuReadsAsOne) {
  const char* expect = std::getenv("NEUROCLOTH_EXPECT_CPU");
  if (expect == nullptr || std::string(expect) != "baseline")
    GTEST_SKIP() << "run natively (ctest's core_tests_on_a_baseline_cpu runs it emulated)";
  EXPECT_FALSE(cpu_reports_avx512());
  EXPECT_EQ(resolved(SpringKernel::automatic), SpringKernel::portable);
}

}  // namespace
}  // namespace neurocloth
