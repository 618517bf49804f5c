#pragma once
// A small plot of one linguistic variable: every term's membership function
// over the variable's range, each in its own colour, with a value marked.
#include <imgui.h>

#include "fuzzy/linguistic_variable.h"

namespace neurocloth {

// `value` is marked by a vertical line (the current input, or the derived
// output). Singletons are drawn as sticks; Sugeno linear consequents have no
// curve and are named instead.
void membership_plot(const fuzzy::LinguisticVariable& variable, double value, ImVec2 size);

}  // namespace neurocloth
