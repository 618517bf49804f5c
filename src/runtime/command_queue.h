#pragma once
// The commands posted to the simulation thread, in order. Posting takes the
// mutex only to push; the simulation thread takes the whole queue at once
// between steps, so neither ever waits for the other's work.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>

#include "runtime/sim_command.h"

namespace neurocloth {

class CommandQueue {
 public:
  void post(SimCommand command);
  // Simulation thread: moves every queued command into `out` (which it empties
  // first). False once stop() was called.
  bool take_all(std::deque<SimCommand>& out);
  // Simulation thread: `count` commands taken are now applied (and visible in
  // the status), which releases wait_until_done().
  void mark_done(long count);
  // Simulation thread, when it has nothing to step: sleeps until a command
  // arrives, stop() is called or `timeout` passes.
  void wait_for_work(std::chrono::duration<double> timeout);
  // Blocks until every command posted before the call is applied (or stop()).
  void wait_until_done() const;
  // The same for at most `timeout`: false when commands were still pending then.
  bool wait_until_done_for(std::chrono::duration<double> timeout) const;
  void stop();
  // True once stop() was called: read between steps by a long command, which
  // then stops early rather than hold the thread's stop (and join) for minutes.
  bool stopping() const { return stopping_.load(std::memory_order_relaxed); }

 private:
  mutable std::mutex mutex_;
  std::condition_variable work_;          // the simulation thread waits here
  mutable std::condition_variable done_;  // wait_until_done() waits here
  std::deque<SimCommand> queue_;
  long posted_ = 0, done_count_ = 0;
  bool stopped_ = false;
  std::atomic<bool> stopping_{false};  // stopped_, readable without the mutex
};

}  // namespace neurocloth
