#pragma once
// The progress line of an iterative command (fit, tune-rules): updated in place
// on a terminal, one line per iteration otherwise (a pipe, a log file):
//   iteration 12/100  <what the command says>  ETA <= 40 s
#include <string>

#include "learn/optim/optimizer.h"

namespace neurocloth {

class ProgressLine {
 public:
  ProgressLine(int max_iterations, double time_budget);

  // `details`: the command's own fields (loss, RMS, parameters), two spaces apart.
  void show(const IterationInfo& it, const std::string& details);
  // Ends an in-place line so the next output starts on its own line.
  void close();

 private:
  // The run may converge sooner: the budgets give an upper bound.
  std::string eta(const IterationInfo& it) const;

  int max_iterations_;
  double time_budget_;
  bool terminal_;
  bool open_ = false;
};

}  // namespace neurocloth
