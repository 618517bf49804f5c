#pragma once
// A test run once with each spring kernel (spring_kernel.h) this CPU has: the
// portable one everywhere, the AVX-512 one where the CPU runs it (skipped
// elsewhere, saying why). For results that the last bits decide (a fit that
// stops on a budget, a blow-up the growth test catches between checks), each
// kernel repeats its own bits on every CPU, so each is checked against the
// figures measured with it.
#include <gtest/gtest.h>

#include <string>

#include "core/network/spring_kernel.h"
#include "core/scene/scene.h"

namespace neurocloth::test {

class ByKernel : public ::testing::TestWithParam<SpringKernel> {
 protected:
  void SetUp() override {
    if (!kernel_unavailable(GetParam()).empty()) GTEST_SKIP() << kernel_unavailable(GetParam());
  }
  bool avx512() const { return GetParam() == SpringKernel::avx512; }
  // `scene` run (and fitted) with this test's kernel.
  Scene with_kernel(Scene scene) const {
    scene.solver.kernel = GetParam();
    return scene;
  }
};

inline std::string kernel_test_name(const ::testing::TestParamInfo<SpringKernel>& info) {
  return to_string(info.param);
}

}  // namespace neurocloth::test

// INSTANTIATE_BY_KERNEL(Suite): Suite (derived from test::ByKernel) once per kernel.
#define INSTANTIATE_BY_KERNEL(suite)                                                        \
  INSTANTIATE_TEST_SUITE_P(, suite,                                                         \
                           ::testing::Values(SpringKernel::portable, SpringKernel::avx512), \
                           ::neurocloth::test::kernel_test_name)
