#pragma once
// A fit's loss curve: the loss at the start and after every iteration, log-log
// (the loss spans decades; so do the iterations of a long fit), with the best
// loss as a dashed rule. The start point sits at x = 1, iteration k at k + 1.
#include <string>
#include <vector>

#include "chart/loglog_chart.h"

namespace neurocloth {

struct LossPoint {
  int iteration = 0;  // 0: the start point
  double loss = 0;
};

ChartSpec loss_chart_spec(const std::vector<LossPoint>& curve, const std::string& title);

}  // namespace neurocloth
