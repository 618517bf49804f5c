#include "render/legend_text.h"

namespace neurocloth {
namespace {

constexpr float kGlyphWidth = 0.55f;  // of the height
constexpr float kAdvance = 0.8f;      // of the height, glyph plus spacing

// Seven segments as (x0, y0, x1, y1) in a glyph of width 1 and height 1, y up:
// a top, b top right, c bottom right, d bottom, e bottom left, f top left, g middle.
constexpr float kSegment[7][4] = {{0, 1, 1, 1},    {1, 1, 1, 0.5f}, {1, 0.5f, 1, 0},   {0, 0, 1, 0},
                                  {0, 0, 0, 0.5f}, {0, 0.5f, 0, 1}, {0, 0.5f, 1, 0.5f}};
// Which segments each digit lights (bit k = segment k).
constexpr unsigned char kDigit[10] = {0x3f, 0x06, 0x5b, 0x4f, 0x66, 0x6d, 0x7d, 0x07, 0x7f, 0x6f};

void add(std::vector<float>& out, float x, float y, float w, float h, float x0, float y0, float x1,
         float y1) {
  out.insert(out.end(), {x + x0 * w, y - y0 * h, x + x1 * w, y - y1 * h});
}

// A small square around (cx, cy) in glyph units.
void add_dot(std::vector<float>& out, float x, float y, float w, float h, float cx, float cy) {
  const float r = 0.08f;
  add(out, x, y, w, h, cx - r, cy - r, cx + r, cy - r);
  add(out, x, y, w, h, cx + r, cy - r, cx + r, cy + r);
  add(out, x, y, w, h, cx + r, cy + r, cx - r, cy + r);
  add(out, x, y, w, h, cx - r, cy + r, cx - r, cy - r);
}

}  // namespace

float append_label(const std::string& text, float x, float y, float height,
                   std::vector<float>& segments) {
  const float w = kGlyphWidth * height;
  float at = x;
  for (const char c : text) {
    if (c >= '0' && c <= '9') {
      for (int k = 0; k < 7; ++k)
        if (kDigit[c - '0'] & (1u << k))
          add(segments, at, y, w, height, kSegment[k][0], kSegment[k][1], kSegment[k][2],
              kSegment[k][3]);
    } else if (c == '-') {
      add(segments, at, y, w, height, 0, 0.5f, 1, 0.5f);
    } else if (c == '.') {
      add_dot(segments, at, y, w, height, 0.2f, 0.08f);
    } else if (c == '%') {
      add(segments, at, y, w, height, 0, 0, 1, 1);
      add_dot(segments, at, y, w, height, 0.15f, 0.82f);
      add_dot(segments, at, y, w, height, 0.85f, 0.18f);
    }
    at += (c == '.' ? 0.5f : kAdvance) * height;
  }
  return at - x;
}

float label_width(const std::string& text, float height) {
  std::vector<float> scratch;
  return append_label(text, 0, 0, height, scratch);
}

}  // namespace neurocloth
