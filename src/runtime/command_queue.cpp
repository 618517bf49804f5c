#include "runtime/command_queue.h"

namespace neurocloth {

void CommandQueue::post(SimCommand command) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    queue_.push_back(std::move(command));
    ++posted_;
  }
  work_.notify_one();
}

bool CommandQueue::take_all(std::deque<SimCommand>& out) {
  out.clear();
  std::lock_guard<std::mutex> lock(mutex_);
  out.swap(queue_);
  return !stopped_;
}

void CommandQueue::mark_done(long count) {
  if (count == 0) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_count_ += count;
  }
  done_.notify_all();
}

void CommandQueue::wait_for_work(std::chrono::duration<double> timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  work_.wait_for(lock, timeout, [this] { return !queue_.empty() || stopped_; });
}

void CommandQueue::wait_until_done() const {
  std::unique_lock<std::mutex> lock(mutex_);
  const long target = posted_;
  done_.wait(lock, [&] { return done_count_ >= target || stopped_; });
}

bool CommandQueue::wait_until_done_for(std::chrono::duration<double> timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  const long target = posted_;
  return done_.wait_for(lock, timeout, [&] { return done_count_ >= target || stopped_; }) &&
         done_count_ >= target;
}

void CommandQueue::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
  }
  stopping_.store(true, std::memory_order_relaxed);
  work_.notify_all();
  done_.notify_all();
}

}  // namespace neurocloth
