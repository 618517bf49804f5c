#pragma once
// A small plot of one linguistic variable: every term's membership function
// over the variable's range, each in its own colour, with a value marked.
#include <imgui.h>

#include "core/fuzzy/linguistic_variable.h"

namespace neurocloth {

// `value` is marked by a vertical line (the current input, or the derived
// output). Singletons are drawn as sticks; Sugeno linear consequents have no
// curve and are named instead.
void membership_plot(const fuzzy::LinguisticVariable& variable, double value, ImVec2 size);

// Keeps the first and last of `n` points and those off the line from the last
// kept point to the next one by more than a twentieth of a pixel, in place;
// returns how many. A piecewise-linear term's samples lie on a few segments, so
// its curve draws the same with a handful of them. ImGui draws a thick
// anti-aliased segment as six triangles and llvmpipe pays for each: with every
// sample, the Material panel's curves were 15k triangles, half of a 128x128
// cloth's (docs/rendering.md, "Cost").
int drop_collinear(ImVec2* points, int n);

}  // namespace neurocloth
