#include "trade_table.h"

#include <cstdio>
#include <stdexcept>

namespace neurocloth {

SolverSettings settings_for(const TradeRow& row, SolverSettings base) {
  base.dt = row.dt;
  if (row.method == kAdaptiveMethod) {
    base.integrator = IntegratorKind::network;
    base.adaptive = true;
    base.adaptive_settings.safety = row.value;
    return base;
  }
  const auto kind = parse_integrator(row.method);
  if (!kind) throw std::invalid_argument("unknown method '" + row.method + "'");
  base.integrator = *kind;
  base.adaptive = false;
  if (row.iterations != 0) {
    if (*kind != IntegratorKind::projective)
      throw std::invalid_argument(row.method + " takes no iterations (only projective iterates)");
    base.iterations = row.iterations;
  }
  return base;
}

std::string line_name(const std::string& method, int iterations) {
  if (iterations == 0) return method;
  return method + " " + std::to_string(iterations) + " it.";
}

std::string line_name(const TradeRow& row) {
  return line_name(row.method, row.iterations);
}

std::string describe_setting(const TradeRow& row) {
  char s[160];
  if (row.method == kAdaptiveMethod)
    std::snprintf(s, sizeof s, "%s, safety %.4g (t_delta %.4g s)", row.method.c_str(), row.value,
                  row.dt);
  else
    std::snprintf(s, sizeof s, "%s, dt %.4g s", line_name(row).c_str(), row.dt);
  return s;
}

}  // namespace neurocloth
