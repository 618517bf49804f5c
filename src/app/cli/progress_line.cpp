#include "app/cli/progress_line.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "app/cli/long_run.h"

namespace neurocloth {

ProgressLine::ProgressLine(int max_iterations, double time_budget)
    : max_iterations_(max_iterations),
      time_budget_(time_budget),
      terminal_(isatty(fileno(stdout)) != 0) {}

void ProgressLine::show(const IterationInfo& it, const std::string& details) {
  const std::string line = "iteration " + std::to_string(it.iteration) + "/" +
                           std::to_string(max_iterations_) + "  " + details + "  " + eta(it);
  if (terminal_) {
    std::printf("\r%s\x1b[K", line.c_str());
    open_ = true;
  } else {
    std::printf("%s\n", line.c_str());
  }
  std::fflush(stdout);
}

void ProgressLine::close() {
  if (open_) std::printf("\n");
  open_ = false;
}

std::string ProgressLine::eta(const IterationInfo& it) const {
  if (it.iteration == 0) return "ETA -";
  double left = it.seconds / it.iteration * (max_iterations_ - it.iteration);
  if (time_budget_ > 0) left = std::min(left, time_budget_ - it.seconds);
  return "ETA <= " + human_duration(std::max(0.0, left));
}

}  // namespace neurocloth
