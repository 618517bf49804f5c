#pragma once
// Minimising a smooth objective from its value and gradient: what fits the
// network's weights to a reference motion (paper eq. 18-19) and tunes a rule
// base to examples, though nothing here knows of cloth or rules. Two methods
// unconstrained, and one over a convex set (minimize_projected, below):
//  - L-BFGS (LBFGSpp), with a backtracking line search to the Wolfe conditions;
//  - the paper's plain gradient descent, theta <- theta - a grad, with the step
//    a chosen by backtracking until the loss drops by at least 1e-4 a |grad|^2
//    (Armijo), and doubled after every accepted step, so no step size is to be
//    tuned and no step ever raises the loss.
// Both keep the best point of every evaluation, so whatever stops them (a
// budget, Ctrl-C, a NaN, a failed line search), the best parameters seen are
// what comes back, with the reason.
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace neurocloth {

// E(theta); fills `gradient` (dE/dtheta) when it is not null.
using Objective = std::function<double(const Eigen::VectorXd& theta, Eigen::VectorXd* gradient)>;

enum class OptimizerMethod { lbfgs, gradient_descent };
// "lbfgs" or "gd"; false for anything else.
bool parse_optimizer_method(const std::string& name, OptimizerMethod& method);
const char* to_string(OptimizerMethod method);

enum class StopReason {
  loss_small,          // the loss reached loss_tolerance
  gradient_small,      // |grad| fell to gradient_tolerance times its start: a stationary point
  stalled,             // the loss fell by less than stall_tolerance over stall_iterations
  iteration_budget,    // max_iterations done
  time_budget,         // time_budget seconds passed
  stopped,             // the callback or should_stop asked (Ctrl-C, a Stop button)
  not_finite,          // a loss or gradient came back NaN or infinite
  line_search_failed,  // no step along the search direction lowered the loss
};
const char* to_string(StopReason reason);
// Whether the stop is a success (a tolerance met) rather than a budget or a failure.
bool converged(StopReason reason);

struct OptimizerOptions {
  OptimizerMethod method = OptimizerMethod::lbfgs;
  int max_iterations = 100;   // > 0
  double time_budget = 0;     // seconds on `clock`; 0: none
  double loss_tolerance = 0;  // stop when the loss is at most this
  // Stop when |grad| (2-norm) is at most this times |grad| at the start. Relative,
  // because a loss in m^2 can be 1e-10 at the start and still far from its optimum.
  double gradient_tolerance = 1e-9;
  // Stalled: the loss fell by less than stall_tolerance * |loss| over the last
  // stall_iterations iterations (0: never).
  int stall_iterations = 5;
  double stall_tolerance = 1e-6;
  int lbfgs_memory = 6;  // correction pairs L-BFGS keeps
  // Seconds since some fixed instant; default: the steady wall clock. Tests
  // pass a fake one so that budgets do not depend on the machine.
  std::function<double()> clock;
  // Asked before every evaluation of the objective: true ends the run there
  // (Ctrl-C between the evaluations of one line search).
  std::function<bool()> should_stop;
};

// One iteration's end, for the callback: the accepted point.
struct IterationInfo {
  int iteration = 0;    // 0: the start point
  double loss = 0;      // at theta
  int evaluations = 0;  // of the objective so far
  double seconds = 0;   // on the options' clock since the start
  const Eigen::VectorXd& theta;
};
// Called at the start point and after every iteration; false stops the run.
using IterationCallback = std::function<bool(const IterationInfo&)>;

struct OptimizerRecord {
  int iteration = 0;
  double loss = 0;
  int evaluations = 0;
  double seconds = 0;
};

struct OptimizerResult {
  Eigen::VectorXd best_theta;  // the lowest finite loss of every evaluation
  double best_loss = 0;        // NaN when not even the start point had a finite loss
  int iterations = 0;          // completed
  int evaluations = 0;
  double seconds = 0;
  std::vector<OptimizerRecord> history;  // the start point and every iteration
  StopReason reason = StopReason::iteration_budget;
  std::string message;  // one sentence: why it stopped, and what was kept
};

// Minimises `objective` from `start`. Throws std::invalid_argument for
// options out of range (max_iterations < 1, a negative budget or tolerance);
// never throws for what the objective returns. An exception the objective
// throws is passed on.
OptimizerResult minimize(const Objective& objective, const Eigen::VectorXd& start,
                         const OptimizerOptions& options, const IterationCallback& callback = {});

// minimize() from each start in turn, for objectives with plateaus or several
// minima (a rule base's MIN and MAX), keeping the lowest loss of all: the
// callback sees the iterations numbered on across the runs, the time budget
// is shared, and a stop that ends the search rather than a run (Ctrl-C, the
// time budget) ends them all. The result's message says which start won.
OptimizerResult minimize_from(const Objective& objective,
                              const std::vector<Eigen::VectorXd>& starts,
                              const OptimizerOptions& options,
                              const IterationCallback& callback = {});

// Maps any theta onto a closed convex set (need not be the exact Euclidean
// projection, but must leave points of the set where they are).
using Projection = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

// Minimises `objective` over the set from project(start): the spectral
// projected gradient method (SPG; Birgin, Martinez and Raydan 2000). Each
// iteration searches from theta towards P(theta - lambda grad), lambda the
// Barzilai-Borwein step of the last iteration, with a non-monotone Armijo
// backtracking over the last 10 losses; every trial point mixes two points of
// the set, so it stays inside. `options.method` and `lbfgs_memory` are
// ignored; the gradient test is on the projected gradient P(theta - grad) -
// theta, relative to its start (the callback's loss and theta as for minimize).
OptimizerResult minimize_projected(const Objective& objective, const Projection& project,
                                   const Eigen::VectorXd& start, const OptimizerOptions& options,
                                   const IterationCallback& callback = {});

}  // namespace neurocloth
