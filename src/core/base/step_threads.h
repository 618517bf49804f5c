#pragma once
// A small persistent team that splits one sweep of a step (the spring layer,
// the node update) over node ranges: part p of P writes only nodes
// [part_begin(n, p, P), part_begin(n, p + 1, P)). Every node is then summed in
// the same order as on one thread, so the result is bit-identical to one
// thread whatever the team size (docs/network.md, "Threads").
//
// The workers live as long as the team (no thread per step); they spin for a
// few microseconds between sweeps, then sleep on a condition variable, so an
// idle team costs no CPU. One team serves one caller at a time.
#include <array>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace neurocloth {

// The most threads a team may have.
inline constexpr int kMaxStepThreads = 64;

// Below this many nodes a sweep is too short to pay for waking a worker.
inline constexpr std::size_t kMinThreadedNodes = 64 * 64;

// Threads for a batch someone waits for (simulate, tradeoff, the viewer's
// --sim-only): two on a cloth of at least kMinThreadedNodes nodes when the
// machine has two cores and at least one of them idle (the 1-minute load
// average below cores - 1), else one. Results do not depend on it.
int batch_step_threads(std::size_t nodes);

// The first node of part `part` of `parts`: a multiple of 8, so no two parts
// share a cache line of a node array.
inline std::size_t part_begin(std::size_t nodes, int part, int parts) {
  if (part >= parts) return nodes;
  return (nodes * static_cast<std::size_t>(part) / static_cast<std::size_t>(parts)) &
         ~std::size_t{7};
}

class StepThreads {
 public:
  explicit StepThreads(int threads);  // threads >= 1: the caller plus threads - 1 workers
  ~StepThreads();
  StepThreads(const StepThreads&) = delete;
  StepThreads& operator=(const StepThreads&) = delete;

  int size() const { return static_cast<int>(workers_.size()) + 1; }

  // Calls fn(part) for every part 0..size()-1, part 0 on the calling thread, and
  // returns when all are done.
  template <class Fn>
  void run(Fn&& fn) {
    using F = std::remove_reference_t<Fn>;
    run_erased([](void* f, int part) { (*static_cast<F*>(f))(part); }, &fn);
  }

 private:
  void run_erased(void (*call)(void*, int), void* context);
  void work(int part);

  std::vector<std::thread> workers_;
  // The task of the current generation, written before generation_ moves on.
  void (*call_)(void*, int) = nullptr;
  void* context_ = nullptr;
  std::atomic<std::uint64_t> generation_{0};
  std::atomic<int> pending_{0};
  std::atomic<bool> stop_{false};
  std::mutex mutex_;
  std::condition_variable start_, done_;
};

// True when a sweep over a cloth of `nodes` nodes is split among `team`.
inline bool splits(const StepThreads* team, std::size_t nodes) {
  return team != nullptr && team->size() > 1 && nodes >= kMinThreadedNodes;
}

// Calls fn(begin, end) on the parts of [0, items) (a cloth's springs, say):
// one part per member of `team` when there is one and the cloth, of `nodes`
// nodes, is large enough to pay for it, else once, whole, on the calling thread.
template <class Fn>
void for_parts(StepThreads* team, std::size_t nodes, std::size_t items, Fn&& fn) {
  if (!splits(team, nodes)) {
    fn(std::size_t{0}, items);
    return;
  }
  const int parts = team->size();
  team->run([&](int p) { fn(part_begin(items, p, parts), part_begin(items, p + 1, parts)); });
}

// The same on the nodes [0, nodes) themselves.
template <class Fn>
void for_node_parts(StepThreads* team, std::size_t nodes, Fn&& fn) {
  for_parts(team, nodes, nodes, std::forward<Fn>(fn));
}

// Calls fn(0) and fn(1): at once on the team's first two members when it has
// two or more, else one after the other. For work cut in two by the data (not
// by the team), so that the bits do not depend on the team.
template <class Fn>
void run_halves(StepThreads* team, Fn&& fn) {
  if (team != nullptr && team->size() >= 2) {
    team->run([&](int part) {
      if (part < 2) fn(part);
    });
  } else {
    fn(0);
    fn(1);
  }
}

// fn(begin, end) -> T on the same parts as for_node_parts, the results folded
// with combine in part order (so the result depends on the parts, which do
// not depend on the team, only when combine is not associative).
template <class T, class Fn, class Combine>
T reduce_node_parts(StepThreads* team, std::size_t nodes, Fn&& fn, Combine&& combine) {
  if (!splits(team, nodes)) return fn(std::size_t{0}, nodes);
  const int parts = team->size();
  std::array<T, kMaxStepThreads> results{};
  team->run([&](int p) {
    results[p] = fn(part_begin(nodes, p, parts), part_begin(nodes, p + 1, parts));
  });
  T out = results[0];
  for (int p = 1; p < parts; ++p)
    out = combine(out, results[p]);
  return out;
}

// A team a value can own: a copy gets a team of its own of the same size, so
// copies of a simulation never share workers. size() 1 holds no team.
class OwnedStepThreads {
 public:
  OwnedStepThreads() = default;
  explicit OwnedStepThreads(int threads)
      : team_(threads > 1 ? std::make_unique<StepThreads>(threads) : nullptr) {}
  OwnedStepThreads(const OwnedStepThreads& o) : OwnedStepThreads(o.size()) {}
  OwnedStepThreads& operator=(const OwnedStepThreads& o) {
    if (this != &o && o.size() != size()) *this = OwnedStepThreads(o.size());
    return *this;
  }
  OwnedStepThreads(OwnedStepThreads&&) = default;
  OwnedStepThreads& operator=(OwnedStepThreads&&) = default;

  int size() const { return team_ ? team_->size() : 1; }
  StepThreads* get() const { return team_.get(); }

 private:
  std::unique_ptr<StepThreads> team_;
};

}  // namespace neurocloth
