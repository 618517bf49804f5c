#pragma once
// A tiny line-segment font (seven-segment digits, '.', '-' and '%') for the
// strain legend's labels, so the renderer needs no font file or texture.
#include <string>
#include <vector>

namespace neurocloth {

// Appends the segments (x0, y0, x1, y1 in pixels, y down) that write `text`
// with its lower left corner at (x, y) in glyphs `height` tall. Characters
// the font lacks leave a gap. Returns the width written.
float append_label(const std::string& text, float x, float y, float height,
                   std::vector<float>& segments);
float label_width(const std::string& text, float height);

}  // namespace neurocloth
