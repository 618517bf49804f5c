// The legend's segment font writes what it is asked inside the box it claims.
#include "render/legend_text.h"

#include <gtest/gtest.h>

namespace neurocloth {
namespace {

TEST(LegendText, DigitsUseTheirSegments) {
  std::vector<float> eight, one;
  append_label("8", 0, 0, 10, eight);
  append_label("1", 0, 0, 10, one);
  EXPECT_EQ(eight.size(), 7u * 4);  // all seven segments
  EXPECT_EQ(one.size(), 2u * 4);
}

TEST(LegendText, SegmentsStayInsideTheLabelsBox) {
  std::vector<float> s;
  const float x = 100, y = 50, h = 12;
  const float w = append_label("12.5%", x, y, h, s);
  EXPECT_FLOAT_EQ(w, label_width("12.5%", h));
  ASSERT_FALSE(s.empty());
  for (std::size_t i = 0; i < s.size(); i += 2) {
    EXPECT_GE(s[i], x - 1);
    EXPECT_LE(s[i], x + w);
    EXPECT_GE(s[i + 1], y - h - 1);  // y grows downwards: the glyphs rise above the baseline
    EXPECT_LE(s[i + 1], y + 1);
  }
  EXPECT_GT(label_width("100%", h), label_width("0%", h));
}

}  // namespace
}  // namespace neurocloth
