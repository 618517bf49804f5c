#include "runtime/snapshot_exchange.h"

#include <utility>

namespace neurocloth {

namespace {
constexpr std::size_t kInitialPool = 3;  // newest, one a reader still draws, one being filled
}

SnapshotExchange::SnapshotExchange() : pool_(std::make_shared<Pool>()) {
  for (std::size_t i = 0; i < kInitialPool; ++i)
    pool_->slots.push_back(std::make_unique<Slot>());
}

FrameSnapshot& SnapshotExchange::back() {
  if (!back_) {
    for (const auto& slot : pool_->slots)
      if (!slot->held.load(std::memory_order_acquire)) {
        back_ = slot.get();
        break;
      }
    if (!back_) {  // readers hold every buffer: one more
      pool_->slots.push_back(std::make_unique<Slot>());
      back_ = pool_->slots.back().get();
    }
  }
  return back_->frame;
}

void SnapshotExchange::publish() {
  if (!back_) back();
  Slot* slot = back_;
  back_ = nullptr;
  slot->frame.serial = serial_.load(std::memory_order_relaxed) + 1;
  slot->held.store(true, std::memory_order_relaxed);  // only this thread reads it as set
  std::shared_ptr<const FrameSnapshot> fresh(&slot->frame,
                                             [pool = pool_, slot](const FrameSnapshot*) {
                                               slot->held.store(false, std::memory_order_release);
                                             });
  {
    std::lock_guard<std::mutex> lock(mutex_);
    newest_.swap(fresh);
  }
  serial_.store(slot->frame.serial, std::memory_order_relaxed);
  // `fresh` now holds the previous snapshot: released here, outside the lock.
}

std::shared_ptr<const FrameSnapshot> SnapshotExchange::latest() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return newest_;
}

std::size_t SnapshotExchange::pool_size() const {
  return pool_->slots.size();
}

}  // namespace neurocloth
