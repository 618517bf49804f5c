#include "tradeoff/trade_table.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace neurocloth {

double row_error(const TradeRow& row, Metric metric) {
  const double e = row.ensemble[slot(metric)];
  if (!std::isnan(e) || metric != Metric::node_max) return e;
  return row.position_error_max;
}

bool has_metric(const TradeTable& trade, Metric metric) {
  return metric == Metric::node_max ||
         (trade.floor && std::isfinite(trade.floor->p90[slot(metric)]));
}

SolverSettings settings_for(const TradeRow& row, SolverSettings base) {
  base.dt = row.dt;
  if (is_adaptive_method(row.method)) {
    base.integrator = IntegratorKind::network;
    base.adaptive = true;
    base.adaptive_settings.safety = row.value;
    base.damping = row.method == kAdaptiveImplicitMethod ? DampingMode::implicit_springwise
                                                         : DampingMode::explicit_force;
    return base;
  }
  const auto kind = parse_integrator(row.method);
  if (!kind) throw std::invalid_argument("unknown method '" + row.method + "'");
  base.integrator = *kind;
  base.adaptive = false;
  if (row.iterations != 0) {
    if (!iterates_per_step(*kind))
      throw std::invalid_argument(row.method +
                                  " takes no iterations (only projective and vbd iterate)");
    base.iterations = row.iterations;
  }
  if (row.linear_tolerance != 0) {
    if (*kind != IntegratorKind::implicit_euler)
      throw std::invalid_argument(row.method +
                                  " takes no linear tolerance (only implicit_euler solves)");
    base.linear_tolerance = row.linear_tolerance;
  }
  return base;
}

namespace {

// "1e-6" rather than printf's "1e-06": the tolerance as a person writes it.
std::string short_number(double v) {
  char s[40];
  std::snprintf(s, sizeof s, "%.3g", v);
  std::string t = s;
  const std::size_t e = t.find("e-0");
  if (e != std::string::npos) t.erase(e + 2, 1);
  return t;
}

}  // namespace

std::string line_name(const TradeRow& row) {
  if (row.iterations != 0) return row.method + " " + std::to_string(row.iterations) + " it.";
  if (row.linear_tolerance != 0) return row.method + " tol " + short_number(row.linear_tolerance);
  return row.method;
}

std::string describe_setting(const TradeRow& row) {
  char s[160];
  if (is_adaptive_method(row.method))
    std::snprintf(s, sizeof s, "%s, safety %.4g (t_delta %.4g s)", row.method.c_str(), row.value,
                  row.dt);
  else
    std::snprintf(s, sizeof s, "%s, dt %.4g s", line_name(row).c_str(), row.dt);
  return s;
}

}  // namespace neurocloth
