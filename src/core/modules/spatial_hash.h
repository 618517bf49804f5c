#pragma once
// A uniform grid of cubic cells, hashed into a table, holding axis-aligned boxes
// (one per item, e.g. a triangle's bounds grown by a contact distance). Asked
// for a point, it returns the items whose box contains the point: only the
// items filed under the point's cell are looked at, so a query costs the
// handful of boxes near the point rather than all of them.
//
// Built by counting sort (count per bucket, prefix sum, fill): the buffers are
// sized once and reused, so rebuilding every step allocates nothing once the
// entry buffer has grown to the cloth's needs, and items come out of a bucket in
// item order, which keeps the callers deterministic.
//
// Header-only so that it needs no build-file entry of its own.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace neurocloth {

struct Aabb {
  double lo[3];
  double hi[3];
  bool contains(const double p[3]) const {
    return p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && p[2] >= lo[2] &&
           p[2] <= hi[2];
  }
};

class SpatialHash {
 public:
  // A box spanning more cells than this is not filed cell by cell but kept in a
  // short list that every query checks: a triangle stretched across the scene
  // (a run that is diverging) must not cost millions of entries.
  static constexpr std::int64_t kMaxCellsPerBox = 512;

  // cell: edge of a cell, m (> 0). `items` boxes are expected; the entry buffer
  // is reserved for `entries_per_item` cells each (a box at most a cell wide
  // touches up to 8).
  void reset(double cell, std::size_t items, std::size_t entries_per_item = 8) {
    cell_ = cell;
    inv_cell_ = 1.0 / cell;
    std::size_t table = 16;
    while (table < 2 * items)
      table *= 2;
    mask_ = table - 1;
    boxes_.assign(items, Aabb{});
    start_.assign(table + 1, 0);
    cursor_.assign(table, 0);
    stamp_.assign(table, -1);
    entries_.clear();
    entries_.reserve(items * entries_per_item);
    big_.clear();
    big_.reserve(items);
  }

  // The boxes to file, one per item: fill them, then build().
  std::vector<Aabb>& boxes() { return boxes_; }
  const std::vector<Aabb>& boxes() const { return boxes_; }

  // Files every box with finite bounds under each cell it overlaps.
  void build() {
    std::fill(start_.begin(), start_.end(), 0);
    std::fill(stamp_.begin(), stamp_.end(), -1);
    big_.clear();
    // Count, once per (bucket, item): two cells of one box may share a bucket.
    std::size_t total = 0;
    for (std::size_t i = 0; i < boxes_.size(); ++i)
      visit_buckets(i, true, [&](std::size_t h) {
        ++start_[h + 1];
        ++total;
      });
    for (std::size_t h = 0; h + 1 < start_.size(); ++h)
      start_[h + 1] += start_[h];
    std::copy(start_.begin(), start_.end() - 1, cursor_.begin());
    std::fill(stamp_.begin(), stamp_.end(), -1);
    entries_.resize(total);  // within the reserve once grown: no allocation
    for (std::size_t i = 0; i < boxes_.size(); ++i)
      visit_buckets(i, false,
                    [&](std::size_t h) { entries_[cursor_[h]++] = static_cast<std::int32_t>(i); });
  }

  // Calls fn(item) once for every item whose box contains p: first those filed
  // under p's bucket (ascending), then the oversized ones (ascending).
  template <class Fn>
  void for_each_containing(const double p[3], Fn&& fn) const {
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) return;
    const std::size_t h = bucket(cell_of(p[0]), cell_of(p[1]), cell_of(p[2]));
    for (std::size_t k = start_[h]; k < start_[h + 1]; ++k) {
      const std::int32_t i = entries_[k];
      // The bucket also holds boxes of other cells that hash alike: filter.
      if (boxes_[static_cast<std::size_t>(i)].contains(p)) fn(i);
    }
    for (std::int32_t i : big_)
      if (boxes_[static_cast<std::size_t>(i)].contains(p)) fn(i);
  }

  double cell_size() const { return cell_; }
  std::size_t bytes() const {
    return boxes_.capacity() * sizeof(Aabb) + start_.capacity() * sizeof(std::size_t) +
           cursor_.capacity() * sizeof(std::size_t) + stamp_.capacity() * sizeof(std::int32_t) +
           entries_.capacity() * sizeof(std::int32_t) + big_.capacity() * sizeof(std::int32_t);
  }

 private:
  // Far beyond any cloth, yet small enough that cell counts cannot overflow.
  static constexpr double kCellLimit = 1099511627776.0;  // 2^40

  // Clamping keeps a far-away point's cell defined; the clamp is monotonic, so
  // a box still covers the (clamped) cell of every point it contains.
  std::int64_t cell_of(double v) const {
    const double c = std::floor(v * inv_cell_);
    return static_cast<std::int64_t>(std::clamp(c, -kCellLimit, kCellLimit));
  }

  std::size_t bucket(std::int64_t x, std::int64_t y, std::int64_t z) const {
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull ^
                      static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full ^
                      static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull;
    h ^= h >> 29;
    return static_cast<std::size_t>(h) & mask_;
  }

  // Calls fn(bucket) for each bucket item i's box is filed under, each bucket
  // once per item. An oversized box is filed under none; it goes to big_ when
  // `record_big` (the counting pass: the filling pass must not add it twice).
  template <class Fn>
  void visit_buckets(std::size_t i, bool record_big, Fn&& fn) {
    const Aabb& b = boxes_[i];
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      if (!(std::isfinite(b.lo[a]) && std::isfinite(b.hi[a]) && b.lo[a] <= b.hi[a])) return;
      lo[a] = cell_of(b.lo[a]);
      hi[a] = cell_of(b.hi[a]);
    }
    const std::int64_t nx = hi[0] - lo[0] + 1, ny = hi[1] - lo[1] + 1, nz = hi[2] - lo[2] + 1;
    if (nx > kMaxCellsPerBox || ny > kMaxCellsPerBox || nx * ny > kMaxCellsPerBox ||
        nx * ny * nz > kMaxCellsPerBox) {
      if (record_big) big_.push_back(static_cast<std::int32_t>(i));
      return;
    }
    const auto tag = static_cast<std::int32_t>(i);
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
          const std::size_t h = bucket(x, y, z);
          if (stamp_[h] == tag) continue;
          stamp_[h] = tag;
          fn(h);
        }
  }

  double cell_ = 1.0, inv_cell_ = 1.0;
  std::size_t mask_ = 15;
  std::vector<Aabb> boxes_;
  std::vector<std::size_t> start_;   // bucket h holds entries_[start_[h], start_[h + 1])
  std::vector<std::size_t> cursor_;  // fill position per bucket while building
  std::vector<std::int32_t> stamp_;  // last item counted in each bucket
  std::vector<std::int32_t> entries_;
  std::vector<std::int32_t> big_;  // items whose box spans more than kMaxCellsPerBox cells
};

}  // namespace neurocloth
