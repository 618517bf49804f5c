#include "tradeoff/ordered_jobs.h"

#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace neurocloth {

void run_jobs_in_order(std::size_t n, int workers, const std::function<void(std::size_t)>& job,
                       const std::function<void(std::size_t)>& done) {
  if (workers <= 1) {
    for (std::size_t i = 0; i < n; ++i) {
      job(i);
      done(i);
    }
    return;
  }
  std::mutex mutex;
  std::condition_variable finished_one;
  std::vector<char> finished(n, 0);
  std::vector<std::exception_ptr> errors(n);
  std::size_t next = 0;
  bool failed = false;
  const auto work = [&] {
    for (;;) {
      std::size_t i;
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (failed || next == n) return;
        i = next++;
      }
      std::exception_ptr error;
      try {
        job(i);
      } catch (...) {
        error = std::current_exception();
      }
      {
        std::lock_guard<std::mutex> lock(mutex);
        errors[i] = error;
        if (error) failed = true;
        finished[i] = 1;
      }
      finished_one.notify_all();
    }
  };
  const auto stop = [&] {
    std::lock_guard<std::mutex> lock(mutex);
    failed = true;
  };
  std::vector<std::thread> threads;
  std::exception_ptr first;
  try {
    for (int w = 0; w < workers; ++w)
      threads.emplace_back(work);
    for (std::size_t i = 0; i < n; ++i) {
      {
        std::unique_lock<std::mutex> lock(mutex);
        // A job not started once another failed never will be.
        finished_one.wait(lock, [&] { return finished[i] || (failed && next <= i); });
        if (!finished[i]) break;
        if (errors[i]) {
          first = errors[i];
          break;
        }
      }
      done(i);
    }
  } catch (...) {  // from starting a thread, or from done()
    first = std::current_exception();
  }
  stop();
  for (std::thread& t : threads)
    t.join();
  if (first) std::rethrow_exception(first);
}

}  // namespace neurocloth
