#pragma once
// A bounding-volume hierarchy over axis-aligned boxes (a mesh's triangles, its
// sharp edges): which items may be near a point, a segment or another box.
// What it holds is only boxes and item numbers; what an item is, and the exact
// test against it, belongs to the caller (triangle_bvh.h).
//
// Nodes lie in one flat array in depth-first order: an inner node's first
// child is the next node, its second child is named by `start`, so a walk
// reads forward through memory and a refit is one backward sweep (children
// always come after their parent). Built by a binned surface-area heuristic
// on the boxes' centres; below kSahDepth, or where the centres coincide, by
// halving the count, so no tree is deeper than kMaxDepth whatever its input
// (thousands of identical boxes included) and every walk fits a fixed stack.
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/base/vec3.h"

namespace neurocloth {

struct BoundingBox {
  Vec3 lo = Vec3::Constant(HUGE_VAL);  // empty until grown
  Vec3 hi = Vec3::Constant(-HUGE_VAL);

  void grow(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void grow(const BoundingBox& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  bool overlaps(const Vec3& qlo, const Vec3& qhi) const {
    return (lo.array() <= qhi.array()).all() && (qlo.array() <= hi.array()).all();
  }
};

class BoxTree {
 public:
  static constexpr int kLeafSize = 4;
  // A depth no walk's stack exceeds: SAH splits down to kSahDepth, then at
  // most log2(2^31 / kLeafSize) = 29 halvings for any int32 count.
  static constexpr int kSahDepth = 32;
  static constexpr int kMaxDepth = 64;

  struct Node {
    Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
    std::int32_t start = 0;  // leaf: first of its items in items(); inner: its second child
    std::int32_t count = 0;  // leaf: its number of items (1 .. kLeafSize); inner: 0
    bool leaf() const { return count > 0; }
  };

  // Over boxes[0 .. n): item i is boxes[i]. Reuses the arrays of an earlier
  // build, so a rebuild over no more items than before does not allocate.
  void build(const std::vector<BoundingBox>& boxes);

  // The same items' boxes moved: box_of(i) gives item i's new box. Bottom up,
  // O(n), no allocation; the tree's shape stays, so a large motion makes the
  // boxes looser (rebuild then).
  template <class BoxOf>
  void refit(BoxOf&& box_of);

  // Calls f(item) for every item in a leaf whose box overlaps [lo, hi]
  // (closed): every item whose own box overlaps, and perhaps a few of its
  // leaf-mates whose box does not; the caller's exact test decides.
  template <class F>
  void for_each_overlapping(const Vec3& lo, const Vec3& hi, F&& f) const;

  BoundingBox bounds() const {
    return nodes_.empty() ? BoundingBox{} : BoundingBox{nodes_[0].lo, nodes_[0].hi};
  }
  std::int32_t size() const { return static_cast<std::int32_t>(items_.size()); }
  int depth() const { return depth_; }  // edges from the root to the deepest leaf
  const std::vector<Node>& nodes() const { return nodes_; }
  const std::vector<std::int32_t>& items() const { return items_; }

 private:
  std::int32_t build_node(const std::vector<BoundingBox>& boxes, std::int32_t first,
                          std::int32_t count, int depth);

  std::vector<Node> nodes_;
  std::vector<std::int32_t> items_;  // leaves' items, each leaf's together
  int depth_ = 0;
};

template <class BoxOf>
void BoxTree::refit(BoxOf&& box_of) {
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    Node& node = nodes_[i];
    BoundingBox b;
    if (node.leaf()) {
      for (std::int32_t k = node.start; k < node.start + node.count; ++k)
        b.grow(box_of(items_[static_cast<std::size_t>(k)]));
    } else {
      const Node& second = nodes_[static_cast<std::size_t>(node.start)];
      b = {nodes_[i + 1].lo.cwiseMin(second.lo), nodes_[i + 1].hi.cwiseMax(second.hi)};
    }
    node.lo = b.lo;
    node.hi = b.hi;
  }
}

template <class F>
void BoxTree::for_each_overlapping(const Vec3& lo, const Vec3& hi, F&& f) const {
  if (nodes_.empty()) return;
  std::int32_t stack[kMaxDepth];
  int top = 0;
  std::int32_t i = 0;
  for (;;) {
    const Node& node = nodes_[static_cast<std::size_t>(i)];
    if ((node.lo.array() <= hi.array()).all() && (lo.array() <= node.hi.array()).all()) {
      if (!node.leaf()) {
        stack[top++] = node.start;
        ++i;
        continue;
      }
      for (std::int32_t k = node.start; k < node.start + node.count; ++k)
        f(items_[static_cast<std::size_t>(k)]);
    }
    if (top == 0) return;
    i = stack[--top];
  }
}

}  // namespace neurocloth
