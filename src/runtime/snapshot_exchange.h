#pragma once
// Hands the newest FrameSnapshot from the simulation thread to any number of
// readers (render thread, UI, tests) so that neither side ever waits for the
// other's work.
//
// Why a pool of reference-counted buffers rather than a classic triple buffer:
// latest() returns a shared_ptr the caller may keep as long as it likes (the
// renderer keeps drawing one while fetching the next), and there may be several
// readers; a triple buffer would overwrite a buffer still being read. Here the
// writer fills only a buffer nobody holds:
//  - each pooled buffer carries a `held` flag; it is set when the buffer is
//    published and cleared (release) by the shared_ptr's deleter when the last
//    holder lets go; the writer picks a buffer whose flag it reads clear (acquire),
//    so every read of the old contents happens before the new writes;
//  - the mutex guards only the `newest_` pointer: a reader holds it to copy a
//    shared_ptr, the writer to swap one. Nothing is filled, copied or freed under it;
//  - when readers hold every pooled buffer the pool grows by one: memory then
//    equals what the readers hold plus the one being filled, as with fresh
//    allocations, and in the usual case (one reader) three or four buffers cycle
//    with no allocation but the shared_ptr's control block.
// The deleters keep the pool alive, so a reader may outlive the exchange.
#include <atomic>
#include <memory>
#include <mutex>
#include <vector>

#include "core/scene/frame_snapshot.h"

namespace neurocloth {

class SnapshotExchange {
 public:
  SnapshotExchange();
  SnapshotExchange(const SnapshotExchange&) = delete;
  SnapshotExchange& operator=(const SnapshotExchange&) = delete;

  // Writer (one thread): the buffer to fill next, with whatever it last held
  // (sizes stay, so capture() does not allocate). The same until published.
  FrameSnapshot& back();
  // Writer: makes back() the newest snapshot, with the next serial number.
  void publish();
  // Any thread: the newest published snapshot (null only before the first publish).
  std::shared_ptr<const FrameSnapshot> latest() const;
  long published() const { return serial_.load(std::memory_order_relaxed); }
  // Writer thread only: buffers in the pool (for tests: it stays small when readers let go).
  std::size_t pool_size() const;

 private:
  struct Slot {
    FrameSnapshot frame;
    std::atomic<bool> held{false};
  };
  struct Pool {
    std::vector<std::unique_ptr<Slot>> slots;  // touched by the writer only
  };

  std::shared_ptr<Pool> pool_;
  Slot* back_ = nullptr;
  std::atomic<long> serial_{0};
  mutable std::mutex mutex_;  // guards newest_ only
  std::shared_ptr<const FrameSnapshot> newest_;
};

}  // namespace neurocloth
