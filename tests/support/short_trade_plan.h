#pragma once
// A trade plan for tests of one method's sweep: 0.05 s, one sample, two levels,
// every level whatever its error, and budgets no run here comes near, so only
// step counts decide where a sweep stops.
#include <string>

#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth::test {

constexpr double kUnboundedSeconds = 1e6;

inline TradeoffPlan short_trade_plan(const std::string& method) {
  TradeoffPlan plan;
  plan.reference.budget_seconds = kUnboundedSeconds;
  plan.method_budget_seconds = kUnboundedSeconds;
  plan.seconds = 0.05;
  plan.samples = 1;
  plan.max_levels = 2;
  plan.error_floor = 0;  // every level, however accurate
  plan.methods = {method};
  return plan;
}

}  // namespace neurocloth::test
