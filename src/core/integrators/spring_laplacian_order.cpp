#include "core/integrators/spring_laplacian_order.h"

#include <Eigen/OrderingMethods>
#include <algorithm>
#include <cstdlib>
#include <queue>

namespace neurocloth {
namespace {

using Index = std::int32_t;

// The nodes `part` (indices into the whole) in approximate minimum degree
// order of the matrix restricted to them.
std::vector<Index> minimum_degree(const LaplacianPattern& lower, const std::vector<Index>& part,
                                  std::vector<Index>& local) {
  const auto m = static_cast<Index>(part.size());
  for (Index k = 0; k < m; ++k)
    local[static_cast<std::size_t>(part[static_cast<std::size_t>(k)])] = k;
  std::vector<Eigen::Triplet<double, Index>> entries;
  for (Index k = 0; k < m; ++k) {
    for (LaplacianPattern::InnerIterator it(lower, part[static_cast<std::size_t>(k)]); it; ++it) {
      const Index r = local[static_cast<std::size_t>(it.row())];
      if (r >= 0) entries.emplace_back(std::max(r, k), std::min(r, k), 1.0);
    }
  }
  for (const Index node : part)
    local[static_cast<std::size_t>(node)] = -1;
  LaplacianPattern sub(m, m);
  sub.setFromTriplets(entries.begin(), entries.end());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, Index> order;
  Eigen::AMDOrdering<Index>()(sub, order);  // order.indices()[k]: the k-th to eliminate
  std::vector<Index> out(part.size());
  for (Index k = 0; k < m; ++k)
    out[static_cast<std::size_t>(k)] = part[static_cast<std::size_t>(order.indices()[k])];
  return out;
}

// Breadth-first levels from `start` over the nodes marked `mark` in `in`
// (-1: not reached); returns the last node reached.
Index levels_from(const std::vector<std::vector<Index>>& adjacent, const std::vector<Index>& in,
                  Index mark, Index start, std::vector<Index>& level) {
  std::queue<Index> next;
  level[static_cast<std::size_t>(start)] = 0;
  next.push(start);
  Index last = start;
  while (!next.empty()) {
    last = next.front();
    next.pop();
    for (const Index j : adjacent[static_cast<std::size_t>(last)])
      if (in[static_cast<std::size_t>(j)] == mark && level[static_cast<std::size_t>(j)] < 0) {
        level[static_cast<std::size_t>(j)] = level[static_cast<std::size_t>(last)] + 1;
        next.push(j);
      }
  }
  return last;
}

// The nested dissection of `part`'s nodes: cut by a whole breadth-first level
// (an edge joins nodes of one level or of two neighbouring ones, so a level
// separates those before it from those after), the two sides dissected again
// down to kLeaf nodes, each leaf and separator in minimum-degree order. On a
// grid this fills the factor less than one minimum-degree order of the whole.
class Dissection {
 public:
  static constexpr std::size_t kLeaf = 4096;

  explicit Dissection(const LaplacianPattern& lower)
      : lower_(lower),
        n_(static_cast<std::size_t>(lower.cols())),
        adjacent_(n_),
        in_(n_, -1),
        level_(n_, -1),
        local_(n_, -1) {
    for (Index j = 0; j < static_cast<Index>(n_); ++j)
      for (LaplacianPattern::InnerIterator it(lower, j); it; ++it)
        if (it.row() != j) {
          adjacent_[static_cast<std::size_t>(j)].push_back(static_cast<Index>(it.row()));
          adjacent_[static_cast<std::size_t>(it.row())].push_back(j);
        }
  }

  // Appends the order of `part` to `order`; at the top, where the second side
  // and the separator begin (0, 0 when the part was not cut).
  void order(const std::vector<Index>& part, std::vector<Index>& out, Index* half = nullptr,
             Index* separator = nullptr) {
    std::vector<Index> first, second, between;
    if (part.size() < kLeaf || !cut(part, first, second, between)) {
      const std::vector<Index> o = minimum_degree(lower_, part, local_);
      out.insert(out.end(), o.begin(), o.end());
      return;
    }
    order(first, out);
    if (half != nullptr) *half = static_cast<Index>(out.size());
    order(second, out);
    if (separator != nullptr) *separator = static_cast<Index>(out.size());
    const std::vector<Index> s = minimum_degree(lower_, between, local_);
    out.insert(out.end(), s.begin(), s.end());
  }

 private:
  bool cut(const std::vector<Index>& part, std::vector<Index>& first, std::vector<Index>& second,
           std::vector<Index>& between) {
    const Index mark = ++marks_;
    for (const Index i : part)
      in_[static_cast<std::size_t>(i)] = mark;
    // A start with an edge inside the part, then a far node from it.
    Index start = -1;
    for (const Index i : part) {
      for (const Index j : adjacent_[static_cast<std::size_t>(i)])
        if (in_[static_cast<std::size_t>(j)] == mark) start = i;
      if (start >= 0) break;
    }
    if (start < 0) return false;
    auto reset = [&] {
      for (const Index i : part)
        level_[static_cast<std::size_t>(i)] = -1;
    };
    reset();
    const Index far = levels_from(adjacent_, in_, mark, start, level_);
    reset();
    levels_from(adjacent_, in_, mark, far, level_);
    Index deepest = 0;
    long unreached = 0;
    for (const Index i : part) {
      deepest = std::max(deepest, level_[static_cast<std::size_t>(i)]);
      unreached += level_[static_cast<std::size_t>(i)] < 0 ? 1 : 0;
    }
    std::vector<long> count(static_cast<std::size_t>(deepest) + 1, 0);
    for (const Index i : part)
      if (level_[static_cast<std::size_t>(i)] >= 0)
        ++count[static_cast<std::size_t>(level_[static_cast<std::size_t>(i)])];
    // The level that splits the rest most evenly (nodes the walk did not
    // reach have no edge to those it did, and join the first side).
    Index best = -1;
    long best_gap = 0, before = unreached + count[0];
    const long total = static_cast<long>(part.size());
    for (Index m = 1; m < deepest; ++m) {
      const long after = total - before - count[static_cast<std::size_t>(m)];
      const long gap = std::labs(before - after);
      if (before > 0 && after > 0 && (best < 0 || gap < best_gap)) {
        best = m;
        best_gap = gap;
      }
      before += count[static_cast<std::size_t>(m)];
    }
    if (best < 0) return false;
    for (const Index i : part) {
      const Index l = level_[static_cast<std::size_t>(i)];
      (l < best ? first : l > best ? second : between).push_back(i);
    }
    return true;
  }

  const LaplacianPattern& lower_;
  std::size_t n_;
  std::vector<std::vector<Index>> adjacent_;
  std::vector<Index> in_;     // the mark of the part being cut
  std::vector<Index> level_;  // breadth-first levels in it
  std::vector<Index> local_;  // minimum_degree's scratch
  Index marks_ = -1;
};

}  // namespace

void laplacian_order(const LaplacianPattern& lower, std::vector<Index>& place, Index& half,
                     Index& separator) {
  const Index n = static_cast<Index>(lower.cols());
  half = separator = 0;
  std::vector<Index> all(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i)
    all[static_cast<std::size_t>(i)] = i;
  std::vector<Index> order;
  order.reserve(all.size());
  Dissection(lower).order(all, order, &half, &separator);
  place.assign(static_cast<std::size_t>(n), 0);
  for (std::size_t k = 0; k < order.size(); ++k)
    place[static_cast<std::size_t>(order[k])] = static_cast<Index>(k);
}

}  // namespace neurocloth
