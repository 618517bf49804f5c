#include "chart/loss_chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace neurocloth {

ChartSpec loss_chart_spec(const std::vector<LossPoint>& curve, const std::string& title) {
  ChartSpec spec;
  spec.title = title;
  spec.x_label = "1 + iteration (the start point at 1)";
  spec.y_label = "loss E (m\xC2\xB2)";
  ChartSeries loss{"loss", Rgb{0.12, 0.38, 0.75}, {}};
  double best = INFINITY;
  for (const LossPoint& p : curve) {
    loss.points.push_back({double(p.iteration + 1), p.loss, false});
    if (std::isfinite(p.loss) && p.loss > 0) best = std::min(best, p.loss);
  }
  spec.series.push_back(std::move(loss));
  if (std::isfinite(best)) {
    char label[48];
    std::snprintf(label, sizeof label, "best %.4g", best);
    spec.rules.push_back({best, label});
  }
  return spec;
}

}  // namespace neurocloth
