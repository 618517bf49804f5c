#pragma once
// A uniform grid of cubic cells, hashed into a table, holding axis-aligned boxes
// (one per item, e.g. a triangle's bounds grown by a contact distance). Asked
// for a point, it returns the items whose box contains the point, looking only
// at the boxes filed near the point's cell instead of at all of them.
//
// A "loose" grid: a box is filed under the cell of its low corner only (under
// more cells only when it is wider than a cell), and a query looks in the
// point's cell and its 7 neighbours on the low side. With cells at least as wide
// as a typical box, a rebuild costs one entry per box, which matters because it
// runs after every step.
//
// Built by counting sort (count per bucket, prefix sum, fill): the buffers are
// sized once and reused, so rebuilding every step allocates nothing once the
// entry buffer has grown to the cloth's needs, and a bucket lists its items in
// ascending order, which keeps callers deterministic. Each entry carries a copy
// of its box in floats, rounded outwards: a query then reads one contiguous run
// per bucket, and a box may only grow by the rounding (a caller tests exactly).
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
  // A box filed under more cells than this goes instead to a short list that
  // every query checks: a triangle stretched across the scene (a run that is
  // diverging) must not cost millions of entries.
  static constexpr std::int64_t kMaxCellsPerBox = 512;

  // cell: edge of a cell, m (> 0), ideally about the width of a box. `items`
  // boxes are expected; entries are reserved for 2 per box (most boxes are
  // filed once), and the buffer grows in the first steps if a scene needs more.
  void reset(double cell, std::size_t items) {
    inv_cell_ = 1.0 / cell;
    std::size_t table = 16;
    while (table < 2 * items)
      table *= 2;
    mask_ = table - 1;
    boxes_.assign(items, Aabb{});
    start_.assign(table + 1, 0);
    cursor_.assign(table, 0);
    home_.assign(items, kNowhere);
    seen_.assign(items, 0);
    entries_.clear();
    entries_.reserve(2 * items);
    big_.clear();
    big_.reserve(items);
  }

  // The boxes to file, one per item: fill them, then build().
  std::vector<Aabb>& boxes() { return boxes_; }

  // Files every box with finite bounds (a box with a NaN is left out).
  void build() {
    std::fill(start_.begin(), start_.end(), 0);
    big_.clear();
    std::size_t total = 0;
    for (std::size_t i = 0; i < boxes_.size(); ++i) {
      std::size_t last = 0;
      const std::int64_t cells = visit_cells(i, [&](std::size_t h) {
        ++start_[h + 1];
        last = h;
      });
      if (cells < 0) big_.push_back(static_cast<std::int32_t>(i));
      total += static_cast<std::size_t>(std::max<std::int64_t>(cells, 0));
      home_[i] = cells == 1 ? static_cast<std::int64_t>(last) : cells > 1 ? kSeveral : kNowhere;
    }
    for (std::size_t h = 0; h + 1 < start_.size(); ++h)
      start_[h + 1] += start_[h];
    std::copy(start_.begin(), start_.end() - 1, cursor_.begin());
    entries_.resize(total);  // within the reserve once grown: no allocation
    for (std::size_t i = 0; i < boxes_.size(); ++i) {
      if (home_[i] == kNowhere) continue;
      const Entry e = entry(i, home_[i] == kSeveral);
      if (home_[i] >= 0)
        entries_[cursor_[static_cast<std::size_t>(home_[i])]++] = e;
      else
        visit_cells(i, [&](std::size_t h) { entries_[cursor_[h]++] = e; });
    }
    std::fill(seen_.begin(), seen_.end(), 0);
    query_ = 0;
  }

  // Calls fn(item) once for every item whose box contains p (and perhaps for
  // one whose box misses p by a float's rounding), in an order fixed by the
  // boxes and p alone.
  template <class Fn>
  void for_each_containing(const double p[3], Fn&& fn) {
    if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]))) return;
    // Rounding to nearest (and the clamp) are monotonic: inside the exact box,
    // inside the outward-rounded one.
    const float q[3] = {to_float(p[0]), to_float(p[1]), to_float(p[2])};
    // A box filed under several cells may be met twice among the 8: it is
    // marked as offered to this query. A box filed once can be met twice only
    // through two cells sharing a bucket, which the bucket check rules out.
    const std::uint32_t mark = ++query_;
    const std::int64_t c[3] = {cell_of(p[0]), cell_of(p[1]), cell_of(p[2])};
    std::size_t probed[8];
    int n = 0;
    for (std::int64_t dx = -1; dx <= 0; ++dx)
      for (std::int64_t dy = -1; dy <= 0; ++dy)
        for (std::int64_t dz = -1; dz <= 0; ++dz) {
          const std::size_t h = bucket(c[0] + dx, c[1] + dy, c[2] + dz);
          if (std::find(probed, probed + n, h) != probed + n) continue;
          probed[n++] = h;
          for (std::size_t k = start_[h], end = start_[h + 1]; k < end; ++k) {
            const Entry& e = entries_[k];
            if (!e.contains(q)) continue;
            if (e.item < 0) {
              const auto i = static_cast<std::size_t>(~e.item);
              if (seen_[i] == mark) continue;
              seen_[i] = mark;
              fn(~e.item);
            } else {
              fn(e.item);
            }
          }
        }
    for (std::int32_t i : big_)
      if (boxes_[static_cast<std::size_t>(i)].contains(p)) fn(i);
  }

  std::size_t bytes() const {
    return boxes_.capacity() * sizeof(Aabb) + start_.capacity() * sizeof(std::size_t) +
           cursor_.capacity() * sizeof(std::size_t) + home_.capacity() * sizeof(std::int64_t) +
           seen_.capacity() * sizeof(std::uint32_t) + entries_.capacity() * sizeof(Entry) +
           big_.capacity() * sizeof(std::int32_t);
  }

 private:
  // Far beyond any cloth, yet small enough that cell counts cannot overflow.
  static constexpr double kCellLimit = 1099511627776.0;  // 2^40
  // home_ values besides a bucket.
  static constexpr std::int64_t kSeveral = -1, kNowhere = -2;

  struct Entry {
    float lo[3], hi[3];
    std::int32_t item;  // ~item when the box is filed under several cells
    // One branch instead of six: which test fails is hard to predict.
    bool contains(const float p[3]) const {
      return (p[0] >= lo[0]) & (p[0] <= hi[0]) & (p[1] >= lo[1]) & (p[1] <= hi[1]) &
             (p[2] >= lo[2]) & (p[2] <= hi[2]);
    }
  };

  Entry entry(std::size_t i, bool several) const {
    Entry e;
    for (int a = 0; a < 3; ++a) {
      // Moved out by 2^-20 of the magnitude, more than a float's rounding
      // (2^-24), before rounding: the float box holds the double one.
      const double lo = boxes_[i].lo[a], hi = boxes_[i].hi[a];
      e.lo[a] = to_float(lo - (std::abs(lo) * 0x1p-20 + 1e-30));
      e.hi[a] = to_float(hi + (std::abs(hi) * 0x1p-20 + 1e-30));
    }
    const auto item = static_cast<std::int32_t>(i);
    e.item = several ? ~item : item;
    return e;
  }

  // Within float range whatever the input (far beyond any cloth).
  static float to_float(double v) { return static_cast<float>(std::clamp(v, -1e30, 1e30)); }

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

  // Calls fn(bucket) for each cell box i is filed under and returns how many
  // (0: left out, not finite; -1: too many, for big_). A box spanning cells
  // lo..hi of an axis is filed under lo..max(lo, hi - 1): a point in any of its
  // cells q then finds it in q or q - 1, the cells a query looks in.
  template <class Fn>
  std::int64_t visit_cells(std::size_t i, Fn&& fn) const {
    const Aabb& b = boxes_[i];
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      if (!(std::isfinite(b.lo[a]) && std::isfinite(b.hi[a]) && b.lo[a] <= b.hi[a])) return 0;
      lo[a] = cell_of(b.lo[a]);
      hi[a] = std::max(lo[a], cell_of(b.hi[a]) - 1);
    }
    const std::int64_t nx = hi[0] - lo[0] + 1, ny = hi[1] - lo[1] + 1, nz = hi[2] - lo[2] + 1;
    if (nx > kMaxCellsPerBox || ny > kMaxCellsPerBox || nx * ny > kMaxCellsPerBox ||
        nx * ny * nz > kMaxCellsPerBox)
      return -1;
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          fn(bucket(x, y, z));
    return nx * ny * nz;
  }

  double inv_cell_ = 1.0;
  std::size_t mask_ = 15;
  std::vector<Aabb> boxes_;
  std::vector<std::size_t> start_;   // bucket h lists entries_[start_[h], start_[h + 1])
  std::vector<std::size_t> cursor_;  // fill position per bucket while building
  std::vector<std::int64_t> home_;   // per item: its one bucket, kSeveral or kNowhere
  std::vector<std::uint32_t> seen_;  // per item filed more than once: the last query that met it
  std::uint32_t query_ = 0;          // queries since the last build
  std::vector<Entry> entries_;
  std::vector<std::int32_t> big_;  // items filed under too many cells: checked by every query
};

}  // namespace neurocloth
