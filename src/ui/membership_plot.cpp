#include "ui/membership_plot.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "ui/fuzzy_view.h"

namespace neurocloth {

namespace {

constexpr int kSamples = 96;

ImU32 term_colour(int term) {
  static const ImU32 palette[] = {IM_COL32(90, 170, 255, 255), IM_COL32(120, 220, 120, 255),
                                  IM_COL32(255, 170, 60, 255), IM_COL32(230, 100, 200, 255),
                                  IM_COL32(240, 230, 90, 255), IM_COL32(100, 230, 230, 255)};
  return palette[term % static_cast<int>(std::size(palette))];
}

bool piecewise_linear(fuzzy::Shape shape) {
  return shape == fuzzy::Shape::points || shape == fuzzy::Shape::triangle ||
         shape == fuzzy::Shape::trapezoid;
}

}  // namespace

int drop_collinear(ImVec2* p, int n) {
  if (n < 3) return n;
  int kept = 1;
  for (int s = 1; s + 1 < n; ++s) {
    const ImVec2 a = p[kept - 1], b = p[s], c = p[s + 1];
    const float cross = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (std::abs(cross) > 0.05f * std::hypot(c.x - a.x, c.y - a.y)) p[kept++] = b;
  }
  p[kept++] = p[n - 1];
  return kept;
}

void membership_plot(const fuzzy::LinguisticVariable& variable, double value, ImVec2 size) {
  ImDrawList* draw = ImGui::GetWindowDrawList();
  const ImVec2 lo = ImGui::GetCursorScreenPos();
  const ImVec2 hi(lo.x + size.x, lo.y + size.y);
  draw->AddRectFilled(lo, hi, IM_COL32(30, 30, 36, 255));
  draw->AddRect(lo, hi, IM_COL32(90, 90, 100, 255));
  const double span = variable.max > variable.min ? variable.max - variable.min : 1.0;
  const auto px = [&](double x) {
    return lo.x + static_cast<float>((x - variable.min) / span) * size.x;
  };
  const auto py = [&](double mu) { return hi.y - 2 - static_cast<float>(mu) * (size.y - 4); };

  bool has_linear = false;
  for (std::size_t t = 0; t < variable.terms.size(); ++t) {
    const fuzzy::MembershipFunction& f = variable.terms[t].function;
    const ImU32 colour = term_colour(static_cast<int>(t));
    if (f.shape == fuzzy::Shape::linear) {
      has_linear = true;
    } else if (f.shape == fuzzy::Shape::singleton) {
      const float x = px(f.params.at(0));
      draw->AddLine(ImVec2(x, py(0)), ImVec2(x, py(1)), colour, 2);
    } else {
      const std::vector<float> mu = FuzzyView::curve(variable, static_cast<int>(t), kSamples);
      ImVec2 points[kSamples];
      for (int s = 0; s < kSamples; ++s)
        points[s] = ImVec2(lo.x + size.x * s / (kSamples - 1), py(mu[s]));
      // A smooth term keeps every sample: points dropped by their neighbours
      // alone could add up to a visible error along a gentle curve.
      const int count = piecewise_linear(f.shape) ? drop_collinear(points, kSamples) : kSamples;
      draw->AddPolyline(points, count, colour, 0, 1.5f);
    }
  }
  // The current value, clamped into view (inference clamps it the same way).
  const float marker = px(std::clamp(value, variable.min, variable.max));
  draw->AddLine(ImVec2(marker, lo.y), ImVec2(marker, hi.y), IM_COL32(255, 255, 255, 220), 1.5f);
  ImGui::Dummy(size);

  // The legend: term names in their colours.
  for (std::size_t t = 0; t < variable.terms.size(); ++t) {
    if (t > 0) ImGui::SameLine();
    ImGui::TextColored(ImGui::ColorConvertU32ToFloat4(term_colour(static_cast<int>(t))), "%s",
                       variable.terms[t].name.c_str());
  }
  if (has_linear) ImGui::TextDisabled("(Sugeno linear consequents: no curve)");
}

}  // namespace neurocloth
