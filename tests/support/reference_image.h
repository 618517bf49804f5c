#pragma once
// Comparing a frame with a committed reference image (tests/reference/) with
// a tolerance: llvmpipe draws the same pixels on one machine every time, but
// another CPU (another SIMD width) may round an edge differently.
// NEUROCLOTH_UPDATE_REFERENCES=1 rewrites the references instead.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include "support/render_test_support.h"

namespace neurocloth::render_test {

struct ImageDifference {
  double mean_abs = 0;       // per RGB channel, in levels of 255
  double visible_share = 0;  // share of pixels with a channel more than 8 levels off
  double large_share = 0;    // share of pixels with a channel more than 32 levels off
};

inline ImageDifference difference(const Image& a, const std::vector<std::uint8_t>& b) {
  ImageDifference d;
  std::size_t visible = 0, large = 0;
  const std::size_t pixels = std::size_t(a.width) * a.height;
  for (std::size_t i = 0; i < pixels; ++i) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int e = std::abs(int(a.rgba[4 * i + c]) - int(b[4 * i + c]));
      d.mean_abs += e;
      worst = std::max(worst, e);
    }
    visible += worst > 8;
    large += worst > 32;
  }
  d.mean_abs /= 3.0 * double(pixels);
  d.visible_share = double(visible) / double(pixels);
  d.large_share = double(large) / double(pixels);
  return d;
}

inline bool updating_references() {
  const char* v = std::getenv("NEUROCLOTH_UPDATE_REFERENCES");
  return v && *v && std::string(v) != "0";
}

// Within 2 levels on average, under 1% of pixels off by more than 32 (an edge
// rounded the other way) and under 2% off by more than 8: a change of shading
// across the cloth, which moves many pixels a little, does not pass.
inline void expect_matches_reference(const Image& image, const std::string& name) {
  const std::string reference = std::string(NEUROCLOTH_REFERENCE_DIR) + "/" + name + ".png";
  if (updating_references()) {
    write_png(reference, image.rgba, image.width, image.height);
    std::printf("updated %s\n", reference.c_str());
  }
  const std::filesystem::path actual =
      std::filesystem::path(NEUROCLOTH_TEST_TMP) / "render" / (name + ".actual.png");
  std::filesystem::create_directories(actual.parent_path());
  write_png(actual.string(), image.rgba, image.width, image.height);
  if (!std::filesystem::exists(reference)) {
    ADD_FAILURE() << "no reference image " << reference
                  << " (NEUROCLOTH_UPDATE_REFERENCES=1 writes it; this frame: " << actual << ")";
    return;
  }
  int w = 0, h = 0;
  const std::vector<std::uint8_t> expected = read_png(reference, w, h);
  ASSERT_EQ(w, image.width);
  ASSERT_EQ(h, image.height);
  const ImageDifference d = difference(image, expected);
  EXPECT_LT(d.mean_abs, 2.0) << name << ": compare " << actual << " with " << reference;
  EXPECT_LT(d.large_share, 0.01) << name << ": compare " << actual << " with " << reference;
  EXPECT_LT(d.visible_share, 0.02) << name << ": compare " << actual << " with " << reference;
}

}  // namespace neurocloth::render_test
