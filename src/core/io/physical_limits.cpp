#include "core/io/physical_limits.h"

#include <cstdio>

namespace neurocloth {

std::string Limit::refusal(double got) const {
  char buf[96];
  std::snprintf(buf, sizeof buf, "must be in [%g, %g]%s%s (got %g): ", low, high, *unit ? " " : "",
                unit, got);
  return buf + std::string(meaning);
}

std::string show_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

}  // namespace neurocloth
