#pragma once
// A small pool for independent jobs whose results must come out in one order
// whatever finishes first: the tradeoff's method lines (tradeoff_sweep.cpp).
#include <cstddef>
#include <functional>

namespace neurocloth {

// Runs job(0..n) on `workers` threads, started in order, and calls done(i) on
// the calling thread for i = 0, 1, ... once job i and every job before it have
// finished. A job that throws stops new ones from starting; when every started
// one has finished, the exception of the first failed job in order is rethrown,
// so which one the caller sees does not depend on timing.
// With `workers` <= 1 it is a plain loop on the calling thread: job(i), done(i).
void run_jobs_in_order(std::size_t n, int workers, const std::function<void(std::size_t)>& job,
                       const std::function<void(std::size_t)>& done);

}  // namespace neurocloth
