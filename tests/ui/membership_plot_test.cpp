#include "ui/membership_plot.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace neurocloth {
namespace {

// Distance from p to the segment a-b, in pixels.
float segment_distance(ImVec2 p, ImVec2 a, ImVec2 b) {
  const float dx = b.x - a.x, dy = b.y - a.y;
  const float len2 = dx * dx + dy * dy;
  const float t =
      len2 > 0 ? std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / len2, 0.0f, 1.0f) : 0.0f;
  return std::hypot(p.x - (a.x + t * dx), p.y - (a.y + t * dy));
}

TEST(DropCollinear, KeepsTheCorners) {
  std::vector<ImVec2> p = {{0, 0}, {1, 0}, {2, 0}, {3, 1}, {4, 2}, {5, 3}};
  ASSERT_EQ(drop_collinear(p.data(), int(p.size())), 3);
  EXPECT_EQ(p[0].x, 0);
  EXPECT_EQ(p[1].x, 2);
  EXPECT_EQ(p[2].x, 5);
}

TEST(DropCollinear, ATriangleTermDrawsTheSameWithAHandfulOfPoints) {
  // A triangle 0.1 / 0.35 / 0.65 on [0, 1], sampled as the plot samples it
  // (96 points over 280 x 40 pixels): the corners fall between samples.
  const int n = 96;
  std::vector<ImVec2> samples(n);
  for (int s = 0; s < n; ++s) {
    const double x = double(s) / (n - 1);
    const double mu = std::max(0.0, std::min((x - 0.1) / 0.25, (0.65 - x) / 0.3));
    samples[s] = ImVec2(280.0f * s / (n - 1), 40.0f - 38.0f * float(mu));
  }
  std::vector<ImVec2> kept = samples;
  const int count = drop_collinear(kept.data(), n);
  // The ends, and at each of the three corners the samples either side of it.
  EXPECT_LE(count, 2 + 2 * 3);
  EXPECT_EQ(kept[0].x, samples[0].x);
  EXPECT_EQ(kept[count - 1].x, samples[n - 1].x);
  // Every sample lies on the kept polyline, within a twentieth of a pixel.
  for (const ImVec2& p : samples) {
    float nearest = 1e9f;
    for (int k = 0; k + 1 < count; ++k)
      nearest = std::min(nearest, segment_distance(p, kept[k], kept[k + 1]));
    EXPECT_LT(nearest, 0.05f) << p.x;
  }
}

TEST(DropCollinear, AStraightLineIsItsEnds) {
  std::vector<ImVec2> p(50);
  for (int s = 0; s < 50; ++s)
    p[s] = ImVec2(float(s), 3.0f * float(s) + 1);
  EXPECT_EQ(drop_collinear(p.data(), 50), 2);
  EXPECT_EQ(p[1].x, 49);
}

}  // namespace
}  // namespace neurocloth
