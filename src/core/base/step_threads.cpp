#include "core/base/step_threads.h"

#include <cstdlib>
#include <stdexcept>
#include <string>

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#endif

namespace neurocloth {
namespace {

// About 10-20 microseconds of polling: longer than the gap between two sweeps
// of one step, far shorter than a frame, so a waiting viewer costs nothing.
constexpr int kSpins = 4000;

inline void relax() {
#if defined(__x86_64__) || defined(__i386__)
  _mm_pause();
#else
  std::this_thread::yield();
#endif
}

}  // namespace

int batch_step_threads(std::size_t nodes) {
  const unsigned cores = std::thread::hardware_concurrency();
  if (nodes < kMinThreadedNodes || cores < 2) return 1;
  // A split step waits at every sweep for its slowest part: on a machine whose
  // cores are already busy (measured: load 4-5 on 2 cores made two threads
  // 2x slower than one) the second thread only adds waiting.
  double load = 0;
  if (getloadavg(&load, 1) == 1 && load > static_cast<double>(cores) - 1.0) return 1;
  return 2;
}

StepThreads::StepThreads(int threads) {
  if (threads < 1 || threads > kMaxStepThreads)
    throw std::invalid_argument("StepThreads: 1 to " + std::to_string(kMaxStepThreads) +
                                " threads");
  for (int part = 1; part < threads; ++part)
    workers_.emplace_back([this, part] { work(part); });
}

StepThreads::~StepThreads() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_.store(true, std::memory_order_release);
    generation_.fetch_add(1, std::memory_order_release);
  }
  start_.notify_all();
  for (std::thread& t : workers_)
    t.join();
}

void StepThreads::run_erased(void (*call)(void*, int), void* context) {
  if (workers_.empty()) {
    call(context, 0);
    return;
  }
  call_ = call;
  context_ = context;
  pending_.store(static_cast<int>(workers_.size()), std::memory_order_relaxed);
  {
    // Under the lock, so a worker about to sleep cannot miss the new generation.
    std::lock_guard<std::mutex> lock(mutex_);
    generation_.fetch_add(1, std::memory_order_release);
  }
  start_.notify_all();
  call(context, 0);
  for (int i = 0; i < kSpins && pending_.load(std::memory_order_acquire) != 0; ++i)
    relax();
  if (pending_.load(std::memory_order_acquire) != 0) {
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [this] { return pending_.load(std::memory_order_acquire) == 0; });
  }
}

void StepThreads::work(int part) {
  std::uint64_t seen = 0;
  for (;;) {
    std::uint64_t g = generation_.load(std::memory_order_acquire);
    for (int i = 0; i < kSpins && g == seen; ++i) {
      relax();
      g = generation_.load(std::memory_order_acquire);
    }
    if (g == seen) {
      std::unique_lock<std::mutex> lock(mutex_);
      start_.wait(lock, [&] {
        g = generation_.load(std::memory_order_acquire);
        return g != seen;
      });
    }
    seen = g;
    if (stop_.load(std::memory_order_acquire)) return;
    call_(context_, part);
    if (pending_.fetch_sub(1, std::memory_order_acq_rel) == 1) {
      std::lock_guard<std::mutex> lock(mutex_);  // pairs with the caller's predicate check
      done_.notify_one();
    }
  }
}

}  // namespace neurocloth
