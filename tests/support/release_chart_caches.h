#pragma once
// Included by one file of each test binary that draws charts: after the last
// test, cairo's and fontconfig's caches go, so that the sanitizer build sees
// no memory left behind.
#include <gtest/gtest.h>

#include "chart/loglog_chart.h"

namespace neurocloth::test {

class ReleaseChartCaches : public ::testing::Environment {
 public:
  void TearDown() override { release_chart_caches(); }
};

inline const auto* const kReleaseChartCaches =
    ::testing::AddGlobalTestEnvironment(new ReleaseChartCaches);

}  // namespace neurocloth::test
