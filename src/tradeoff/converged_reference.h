#pragma once
// The trajectory every setting is measured against: RK4 with its step halved
// until halving it once more moves no node, at any sample time, by more than
// `target` of the cloth's size. Contact, friction and gusts sampled once a step
// make a scene non-smooth (and a flapping flag is sensitive to where it starts),
// so it may never get there; then the budget stops the halving and the report
// says what was reached, never more.
#include <functional>
#include <string>
#include <vector>

#include "tradeoff/run_error.h"
#include "tradeoff/sampled_run.h"

namespace neurocloth {

struct ReferencePlan {
  double target = 1e-9;        // relative change between successive halvings to reach
  int max_halvings = 14;       // after the first stable run
  double budget_seconds = 20;  // run cost (run_clock) of all reference runs together
};

struct ReferenceReport {
  double dt = 0;       // the finest RK4 step: the reference itself
  double change = -1;  // max change (relative to size) between the last two halvings; < 0: none
  std::vector<double> change_by_sample;  // the same at each sample time
  double rms_change = -1;                // RMS of the change over nodes and samples
  double target = 1e-9;
  bool met = false;
  int runs = 0;             // RK4 runs made (the diverged ones too)
  double wall_seconds = 0;  // their cost (run_clock) all together
  std::string stopped_by;   // "target", "budget", "halvings" or "diverged"
};

struct ConvergedReference {
  SampledRun run;  // the finest run
  ReferenceReport report;
  // Every other RK4 run made on the way, coarsest first (the diverged ones
  // too): they are the RK4 line of the trade, measured at no extra cost.
  std::vector<SampledRun> coarser;
};

// Halves RK4's step from `first_dt` (a sample interval over a power of two, so
// every step lands on the sample times). `log` is told about each run.
ConvergedReference converge_reference(const Scene& scene, const std::vector<double>& times,
                                      const ErrorScale& scale, double first_dt,
                                      const ReferencePlan& plan,
                                      const std::function<void(const std::string&)>& log = {});

}  // namespace neurocloth
