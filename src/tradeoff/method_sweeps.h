#pragma once
// One method's line of the trade: how each method's settings are swept and
// when its line stops. RK4 reads the reference's own runs; a fixed-step method
// halves its step; projective, vbd and implicit_euler sweep their step at every
// setting of their second knob; adaptive halves its safety factor.
// measure_tradeoff (tradeoff_sweep.h) decides which lines run, and where.
#include <functional>
#include <string>
#include <vector>

#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth {

// What one method's line adds to the table, kept apart until it is merged in
// method order.
struct MethodLine {
  std::vector<TradeRow> rows;
  std::vector<std::string> stops;
  std::vector<std::string> log;  // when not told live
};

// One method's sweep: reads what every line shares, writes only its own line.
struct MethodSweep {
  const Scene& scene;  // the line's own copy
  const TradeoffPlan& plan;
  const std::vector<double>& times;
  const ErrorScale& scale;
  const ConvergedReference& ref;
  const MetricContext& metrics;
  const Ensemble* ensemble;                             // null: none asked for
  const std::function<void(const std::string&)>* live;  // null: say() keeps it in the line
  MethodLine& out;

  // RK4's line: the reference's own coarser runs.
  void rk4();
  void fixed_step(IntegratorKind kind);
  // Projective and vbd have two knobs: the step and the iterations per step.
  void iterating(IntegratorKind kind, const std::vector<int>& counts);
  // So has the implicit step: its step and its conjugate-gradient tolerance.
  void implicit();
  // The paper's propagation, halving its safety factor.
  void adaptive(DampingMode damping);

 private:
  void say(const std::string& s) const;
  void to_ensemble(TradeRow& row, const SampledRun& run) const;
  TradeRow run_row(const SolverSettings& s, const std::string& method, const char* parameter,
                   double value, SampledRun& run);
  void stopped(const std::string& line, const std::string& why);
  bool measure(const SolverSettings& s, const std::string& method, const char* parameter,
               double value, int level, double& line_cost);
  bool at_step_floor(double dt, const std::string& line);
  void two_knobs(IntegratorKind kind, std::vector<SolverSettings> going);
};

}  // namespace neurocloth
