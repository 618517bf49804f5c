#include "core/geometry/box_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace neurocloth {

namespace {

constexpr int kBins = 16;

// Half the surface area: what the heuristic weighs a child's items by (the
// chance a random ray meets it), up to a constant that does not change which
// split is cheapest.
double half_area(const BoundingBox& b) {
  if (!(b.lo.array() <= b.hi.array()).all()) return 0;
  const Vec3 d = b.hi - b.lo;
  return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
}

Vec3 box_centre(const BoundingBox& b) {
  return 0.5 * (b.lo + b.hi);
}

// Which of kBins equal slices of [lo, lo + extent) a centre coordinate falls
// in; the same expression bins and partitions, so both agree on every item.
// A NaN (a box of a NaN vertex) goes to the first slice, never out of range.
int bin_of(double c, double lo, double scale) {
  const double x = (c - lo) * scale;
  if (!(x >= 0)) return 0;
  return x < kBins - 1 ? static_cast<int>(x) : kBins - 1;
}

// A centre's coordinate as the count-halving split orders it: NaN last, so
// the order stays strict and weak.
double order_key(double c) {
  return std::isnan(c) ? HUGE_VAL : c;
}

}  // namespace

void BoxTree::build(const std::vector<BoundingBox>& boxes) {
  const auto n = static_cast<std::int32_t>(boxes.size());
  items_.resize(boxes.size());
  std::iota(items_.begin(), items_.end(), 0);
  nodes_.clear();
  // A leaf holds at least one item, so 2n - 1 nodes at most: no reallocation
  // while building, none at all when rebuilding over no more items.
  nodes_.reserve(boxes.empty() ? 0 : 2 * boxes.size() - 1);
  depth_ = 0;
  if (n > 0) build_node(boxes, 0, n, 0);
  if (depth_ > kMaxDepth) throw std::logic_error("BoxTree: deeper than kMaxDepth");
}

std::int32_t BoxTree::build_node(const std::vector<BoundingBox>& boxes, std::int32_t first,
                                 std::int32_t count, int depth) {
  const auto index = static_cast<std::int32_t>(nodes_.size());
  nodes_.push_back({});
  depth_ = std::max(depth_, depth);
  BoundingBox bounds, centres;
  for (std::int32_t k = first; k < first + count; ++k) {
    const BoundingBox& b = boxes[static_cast<std::size_t>(items_[static_cast<std::size_t>(k)])];
    bounds.grow(b);
    centres.grow(box_centre(b));
  }
  nodes_.back().lo = bounds.lo;
  nodes_.back().hi = bounds.hi;
  if (count <= kLeafSize) {
    nodes_.back().start = first;
    nodes_.back().count = count;
    return index;
  }

  const auto begin = items_.begin() + first, end = begin + count;
  auto centre_of = [&](std::int32_t item) {
    return box_centre(boxes[static_cast<std::size_t>(item)]);
  };
  const Vec3 extent = centres.hi - centres.lo;
  auto split = begin;

  // The binned surface-area heuristic (Wald 2007): on each axis the centres
  // fall into kBins slices; a split between slices costs each side's count
  // times its area. Only splits with items on both sides are weighed, so a
  // chosen split always shrinks both children.
  if (depth < kSahDepth) {
    double best_cost = HUGE_VAL;
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(extent[axis] > 0)) continue;
      const double scale = kBins / extent[axis];
      std::array<BoundingBox, kBins> bin_box;
      std::array<std::int32_t, kBins> bin_count{};
      for (auto it = begin; it != end; ++it) {
        const int b = bin_of(centre_of(*it)[axis], centres.lo[axis], scale);
        bin_box[static_cast<std::size_t>(b)].grow(boxes[static_cast<std::size_t>(*it)]);
        ++bin_count[static_cast<std::size_t>(b)];
      }
      // Right-hand sides swept from the top, then left-hand sides upwards.
      std::array<double, kBins> right_cost{};
      BoundingBox right;
      std::int32_t right_count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        right.grow(bin_box[static_cast<std::size_t>(b)]);
        right_count += bin_count[static_cast<std::size_t>(b)];
        right_cost[static_cast<std::size_t>(b)] = right_count * half_area(right);
      }
      BoundingBox left;
      std::int32_t left_count = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        left.grow(bin_box[static_cast<std::size_t>(b)]);
        left_count += bin_count[static_cast<std::size_t>(b)];
        if (left_count == 0 || left_count == count) continue;
        const double cost =
            left_count * half_area(left) + right_cost[static_cast<std::size_t>(b + 1)];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bin = b;
        }
      }
    }
    if (best_axis >= 0) {
      const double scale = kBins / extent[best_axis];
      split = std::partition(begin, end, [&](std::int32_t item) {
        return bin_of(centre_of(item)[best_axis], centres.lo[best_axis], scale) <= best_bin;
      });
    }
  }

  // Otherwise halve the count along the widest spread of centres, ties by
  // item number: coincident centres still split, and in the same way on every
  // machine.
  if (split == begin || split == end) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (extent[a] > extent[axis]) axis = a;
    split = begin + count / 2;
    std::nth_element(begin, split, end, [&](std::int32_t x, std::int32_t y) {
      const double cx = order_key(centre_of(x)[axis]), cy = order_key(centre_of(y)[axis]);
      return cx < cy || (cx == cy && x < y);
    });
  }

  const auto left_count = static_cast<std::int32_t>(split - begin);
  build_node(boxes, first, left_count, depth + 1);
  const std::int32_t second = build_node(boxes, first + left_count, count - left_count, depth + 1);
  nodes_[static_cast<std::size_t>(index)].start = second;
  nodes_[static_cast<std::size_t>(index)].count = 0;
  return index;
}

}  // namespace neurocloth
