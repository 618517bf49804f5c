// The tradeoff's method lines measured side by side: the same table as one
// after another, merged in method order, logged from the calling thread only,
// and a worker's exception reaching the caller. Also run under TSan (label
// runtime).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "support/test_support.h"
#include "tradeoff/ordered_jobs.h"
#include "tradeoff/tradeoff_sweep.h"

namespace neurocloth {
namespace {

// Every method on a short run of hanging.json, small enough for TSan. No stop
// may depend on timing: the budgets are unbounded, the levels few.
TradeoffPlan tiny_plan(int workers) {
  TradeoffPlan plan;
  plan.seconds = 0.02;
  plan.samples = 2;
  plan.max_levels = 2;
  plan.min_levels = 1;
  plan.projective_iterations = {1, 4};
  plan.vbd_iterations = {1, 4};
  plan.reference.max_halvings = 2;
  plan.reference.budget_seconds = 1e6;
  plan.method_budget_seconds = 1e6;
  plan.workers = workers;
  plan.ensemble.members = 3;  // run on the workers too, and read by every line
  return plan;
}

struct Measured {
  TradeTable table;
  std::vector<std::string> log;
  bool all_on_caller = true;
};

Measured measure(int workers) {
  Measured m;
  const std::thread::id caller = std::this_thread::get_id();
  m.table = measure_tradeoff(test::asset_scene("hanging"), "hanging.json", tiny_plan(workers),
                             [&](const std::string& line) {
                               if (std::this_thread::get_id() != caller) m.all_on_caller = false;
                               m.log.push_back(line);
                             });
  return m;
}

// Equal as bits, NaN equal to NaN (a diverged row has no error).
bool same(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

// `line` with every "<number> s per simulated s", "<number> s thread CPU" and
// "<number> s wall" written COST. (No std::regex: GCC 12's, built with the
// sanitizers, trips -Wmaybe-uninitialized inside the library.)
std::string cost_hidden(std::string line) {
  const auto in_number = [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) ||
           std::islower(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '+';
  };
  for (const std::string unit : {" s per simulated s", " s thread CPU", " s wall"}) {
    for (std::size_t at = line.find(unit); at != std::string::npos; at = line.find(unit, at)) {
      std::size_t start = at;
      while (start > 0 && in_number(line[start - 1]))
        --start;
      if (start == at) {  // no number before it
        at += unit.size();
        continue;
      }
      line.replace(start, at + unit.size() - start, "COST");
      at = start + 4;
    }
  }
  return line;
}

// The log without its cost figures (the one thing that may differ).
std::vector<std::string> without_costs(const std::vector<std::string>& log) {
  std::vector<std::string> out;
  for (const std::string& line : log)
    out.push_back(cost_hidden(line));
  return out;
}

TEST(TradeoffWorkers, HidesCostFiguresOnly) {
  EXPECT_EQ(
      cost_hidden("network dt 0.01: ok, max error 0.0631, rms 0.0104, 0.00114 s per simulated s"),
      "network dt 0.01: ok, max error 0.0631, rms 0.0104, COST");
  EXPECT_EQ(cost_hidden("reference (12 runs, 1.2e-05 s thread CPU), 3 s wall"),
            "reference (12 runs, COST), COST");
  EXPECT_EQ(cost_hidden("nothing to hide, 3 runs"), "nothing to hide, 3 runs");
}

TEST(TradeoffWorkers, TwoWorkersMeasureWhatOneDoesInTheSameOrder) {
  const Measured one = measure(1), two = measure(2);
  const std::vector<TradeRow>& a = one.table.rows;
  const std::vector<TradeRow>& b = two.table.rows;
  ASSERT_EQ(a.size(), b.size());
  // Every method has a line, so an order mistake shows.
  std::vector<std::string> methods;
  for (const TradeRow& r : a)
    if (methods.empty() || methods.back() != r.method) methods.push_back(r.method);
  EXPECT_EQ(methods, (std::vector<std::string>{"network", "explicit_euler", "verlet", "rk4",
                                               "implicit_euler", "projective", "vbd", "adaptive"}));
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("row " + std::to_string(i) + ": " + describe_setting(a[i]));
    EXPECT_EQ(a[i].method, b[i].method);
    EXPECT_EQ(a[i].parameter, b[i].parameter);
    EXPECT_EQ(a[i].value, b[i].value);
    EXPECT_EQ(a[i].dt, b[i].dt);
    EXPECT_EQ(a[i].iterations, b[i].iterations);
    EXPECT_EQ(a[i].steps, b[i].steps);
    EXPECT_EQ(a[i].force_evaluations, b[i].force_evaluations);
    EXPECT_EQ(a[i].rejected_steps, b[i].rejected_steps);
    EXPECT_EQ(a[i].status, b[i].status);
    EXPECT_TRUE(same(a[i].position_error_max, b[i].position_error_max));
    EXPECT_TRUE(same(a[i].position_error_rms, b[i].position_error_rms));
    EXPECT_TRUE(same(a[i].energy_error, b[i].energy_error));
    for (Metric m : kAllMetrics)
      EXPECT_TRUE(same(a[i].ensemble[slot(m)], b[i].ensemble[slot(m)])) << to_string(m);
    EXPECT_GT(b[i].wall_per_simulated_second, 0);
  }
  EXPECT_EQ(one.table.sweep_stops, two.table.sweep_stops);
  EXPECT_FALSE(two.table.sweep_stops.empty());
  EXPECT_EQ(one.table.reference.dt, two.table.reference.dt);
  EXPECT_EQ(one.table.reference.change, two.table.reference.change);
  ASSERT_TRUE(one.table.floor && two.table.floor);
  for (Metric m : kAllMetrics)
    EXPECT_TRUE(same(one.table.floor->p90[slot(m)], two.table.floor->p90[slot(m)])) << to_string(m);
  EXPECT_TRUE(one.all_on_caller);
  EXPECT_TRUE(two.all_on_caller);
  EXPECT_EQ(without_costs(one.log), without_costs(two.log));
}

TEST(TradeoffWorkers, RefusesAWorkerCountOutOfRange) {
  const Scene scene = test::asset_scene("hanging");
  for (int workers : {-1, kMaxTradeoffWorkers + 1})
    EXPECT_THROW(measure_tradeoff(scene, "", tiny_plan(workers)), std::invalid_argument) << workers;
}

TEST(TradeoffWorkers, OneWorkerPerCoreAtMostOnePerLine) {
  EXPECT_EQ(tradeoff_workers(3, 2), 2);
  EXPECT_EQ(tradeoff_workers(2, 6), 2);
  EXPECT_EQ(tradeoff_workers(1, 6), 1);
  EXPECT_EQ(tradeoff_workers(4, 0), 1);
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  EXPECT_EQ(tradeoff_workers(0, 1000), cores);
}

// Jobs that finish in reverse order still come out in order, on the caller.
TEST(OrderedJobs, DoneComesInJobOrderOnTheCallingThread) {
  for (int workers : {1, 2, 3}) {
    constexpr std::size_t n = 8;
    std::vector<int> results(n, -1);
    std::vector<std::size_t> done;
    std::atomic<int> finished{0};
    const std::thread::id caller = std::this_thread::get_id();
    bool on_caller = true;
    run_jobs_in_order(
        n, workers,
        [&](std::size_t i) {
          // A later job does not wait on an earlier one, so nothing here may
          // block on order; only the results are checked.
          results[i] = static_cast<int>(i * i);
          finished.fetch_add(1);
        },
        [&](std::size_t i) {
          if (std::this_thread::get_id() != caller) on_caller = false;
          EXPECT_EQ(results[i], static_cast<int>(i * i));
          done.push_back(i);
        });
    EXPECT_EQ(finished.load(), static_cast<int>(n));
    EXPECT_EQ(done, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7})) << workers;
    EXPECT_TRUE(on_caller);
  }
}

// Jobs 2 and 4 throw: the caller always sees job 2's, after done(0) and done(1)
// only, whichever worker failed first.
TEST(OrderedJobs, TheFirstFailedJobInOrderReachesTheCaller) {
  for (int workers : {1, 2, 4}) {
    for (int round = 0; round < 20; ++round) {
      std::vector<std::size_t> done;
      try {
        run_jobs_in_order(
            6, workers,
            [&](std::size_t i) {
              if (i == 2 || i == 4) throw std::runtime_error("job " + std::to_string(i));
            },
            [&](std::size_t i) { done.push_back(i); });
        ADD_FAILURE() << "no exception with " << workers << " workers";
      } catch (const std::runtime_error& e) {
        EXPECT_EQ(std::string(e.what()), "job 2") << workers << " workers";
      }
      EXPECT_EQ(done, (std::vector<std::size_t>{0, 1})) << workers << " workers";
    }
  }
}

}  // namespace
}  // namespace neurocloth
