#pragma once
// A forward-mode dual number: a value and its derivatives with respect to a
// fixed set of seeds. The fuzzy engine is written once over a scalar type T and
// run with T = double to infer, or T = Dual to get exact derivatives of every
// output with respect to the inputs, the membership-function parameters and the
// consequents in the same pass (what tuning the rule base by gradient needs).
//
// The derivatives are sparse: a membership degree depends on one input and its
// term's few parameters, a rule's activation on its conditions' terms, and only
// the sums that make a centroid reach many seeds. A Dual therefore keeps only
// the seeds it depends on, sorted, and keeps the first few inline, so that most
// operations allocate nothing; a dense vector of every seed made each operation
// allocate and touch all of them (102 for cloth.fcl), which dominated tune-rules.
// Each derivative is the same sum of the same products as with a dense vector:
// a seed missing from one operand is an exact zero there.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

namespace neurocloth::fuzzy {

// The nonzero derivatives of a Dual: (seed, derivative) pairs, seeds ascending.
class SparseGradient {
 public:
  struct Entry {
    std::uint32_t seed;
    double d;
  };
  // Enough for a membership degree (an input and a trapezoid's 4 corners) and
  // most activations (a MIN keeps one condition's).
  static constexpr std::uint32_t kInline = 6;

  SparseGradient() = default;
  SparseGradient(const SparseGradient& o) { copy_from(o); }
  SparseGradient(SparseGradient&& o) noexcept { take(o); }
  SparseGradient& operator=(const SparseGradient& o) {
    if (this != &o) {
      size_ = 0;
      copy_from(o);
    }
    return *this;
  }
  SparseGradient& operator=(SparseGradient&& o) noexcept {
    if (this != &o) take(o);
    return *this;
  }

  std::uint32_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const Entry* begin() const { return data(); }
  const Entry* end() const { return data() + size_; }

  // Room for n entries; discards the current ones.
  void reset(std::uint32_t n) {
    size_ = 0;
    if (n > capacity_) {
      heap_.reset(new Entry[n]);
      capacity_ = n;
    }
  }
  // Appends after reset(); seeds must come ascending.
  void push_back(std::uint32_t seed, double d) { data()[size_++] = {seed, d}; }

  double operator[](std::uint32_t seed) const {
    for (const Entry& e : *this)
      if (e.seed >= seed) return e.seed == seed ? e.d : 0.0;
    return 0.0;
  }

 private:
  Entry* data() { return heap_ ? heap_.get() : inline_; }
  const Entry* data() const { return heap_ ? heap_.get() : inline_; }
  // An inline list is copied as the whole buffer: a fixed-size copy the
  // compiler inlines, where a variable-size one calls memmove.
  void copy_from(const SparseGradient& o) {
    reset(o.size_);
    if (o.heap_)
      std::memcpy(data(), o.heap_.get(), o.size_ * sizeof(Entry));
    else
      std::memcpy(data(), o.inline_, sizeof inline_);  // every capacity is >= kInline
    size_ = o.size_;
  }
  void take(SparseGradient& o) {
    if (o.heap_) {
      heap_ = std::move(o.heap_);
      capacity_ = o.capacity_;
      o.capacity_ = kInline;
    } else {
      heap_.reset();
      capacity_ = kInline;
      std::memcpy(inline_, o.inline_, sizeof inline_);
    }
    size_ = o.size_;
    o.size_ = 0;
  }

  std::uint32_t size_ = 0, capacity_ = kInline;
  std::unique_ptr<Entry[]> heap_;  // when more than kInline seeds were needed
  Entry inline_[kInline];
};

struct Dual {
  double v = 0;
  SparseGradient d;  // empty means "all zero" (a constant)

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: constants convert implicitly
  // The seed variable number `seed`: derivative 1 with respect to itself.
  Dual(double value, std::uint32_t seed) : v(value) {
    d.reset(1);
    d.push_back(seed, 1.0);
  }

  double derivative(std::uint32_t seed) const { return d[seed]; }
};

namespace detail {
// r = a * x + b * y, merging the two seed lists.
inline SparseGradient combine(double a, const SparseGradient& x, double b,
                              const SparseGradient& y) {
  SparseGradient r;
  r.reset(x.size() + y.size());
  const auto* i = x.begin();
  const auto* j = y.begin();
  while (i != x.end() && j != y.end()) {
    if (i->seed < j->seed) {
      r.push_back(i->seed, a * i->d);
      ++i;
    } else if (j->seed < i->seed) {
      r.push_back(j->seed, b * j->d);
      ++j;
    } else {
      r.push_back(i->seed, a * i->d + b * j->d);
      ++i, ++j;
    }
  }
  for (; i != x.end(); ++i)
    r.push_back(i->seed, a * i->d);
  for (; j != y.end(); ++j)
    r.push_back(j->seed, b * j->d);
  return r;
}
inline SparseGradient scale(double a, const SparseGradient& x) {
  SparseGradient r;
  r.reset(x.size());
  for (const auto& e : x)
    r.push_back(e.seed, a * e.d);
  return r;
}
}  // namespace detail

inline Dual make(double v, SparseGradient d) {
  Dual r(v);
  r.d = std::move(d);
  return r;
}
inline Dual operator+(const Dual& a, const Dual& b) {
  return make(a.v + b.v, detail::combine(1, a.d, 1, b.d));
}
inline Dual operator-(const Dual& a, const Dual& b) {
  return make(a.v - b.v, detail::combine(1, a.d, -1, b.d));
}
inline Dual operator-(const Dual& a) {
  return make(-a.v, detail::scale(-1, a.d));
}
inline Dual operator*(const Dual& a, const Dual& b) {
  return make(a.v * b.v, detail::combine(b.v, a.d, a.v, b.d));
}
inline Dual operator/(const Dual& a, const Dual& b) {
  return make(a.v / b.v, detail::combine(1.0 / b.v, a.d, -a.v / (b.v * b.v), b.d));
}
inline Dual& operator+=(Dual& a, const Dual& b) {
  return a = a + b;
}
inline Dual& operator-=(Dual& a, const Dual& b) {
  return a = a - b;
}
inline Dual& operator*=(Dual& a, const Dual& b) {
  return a = a * b;
}
inline bool operator<(const Dual& a, const Dual& b) {
  return a.v < b.v;
}
inline bool operator>(const Dual& a, const Dual& b) {
  return a.v > b.v;
}
inline bool operator<=(const Dual& a, const Dual& b) {
  return a.v <= b.v;
}
inline bool operator>=(const Dual& a, const Dual& b) {
  return a.v >= b.v;
}
inline bool operator==(const Dual& a, const Dual& b) {
  return a.v == b.v;
}

inline Dual sqrt(const Dual& a) {
  const double s = std::sqrt(a.v);
  return make(s, detail::scale(s > 0 ? 0.5 / s : 0.0, a.d));
}
inline Dual exp(const Dual& a) {
  const double e = std::exp(a.v);
  return make(e, detail::scale(e, a.d));
}
inline Dual log(const Dual& a) {
  return make(std::log(a.v), detail::scale(1.0 / a.v, a.d));
}
// |a|^p for p a dual too (generalised bell); a > 0 assumed where p varies.
inline Dual pow(const Dual& a, const Dual& p) {
  const double r = std::pow(a.v, p.v);
  const double da = a.v != 0 ? p.v * std::pow(a.v, p.v - 1) : 0.0;
  const double dp = a.v > 0 ? r * std::log(a.v) : 0.0;
  return make(r, detail::combine(da, a.d, dp, p.d));
}
inline Dual abs(const Dual& a) {
  return a.v < 0 ? -a : a;
}

// The sum of c * a over many Duals a (a sampled centroid's 20001 samples). The
// derivatives gather in a dense buffer indexed by seed, so each term costs its
// own few seeds, not a merge with the sum's many and an allocation. The same
// numbers as adding the products one by one.
class DualSum {
 public:
  void add(double c, const Dual& a) {
    v_ += c * a.v;
    for (const auto& e : a.d) {
      if (e.seed >= d_.size()) {
        d_.resize(e.seed + 1, 0.0);
        present_.resize(e.seed + 1, 0);
      }
      d_[e.seed] += c * e.d;
      present_[e.seed] = 1;
    }
  }
  Dual total() const {
    Dual r(v_);
    std::uint32_t n = 0;
    for (char p : present_)
      n += p;
    r.d.reset(n);
    for (std::uint32_t seed = 0; seed < d_.size(); ++seed)
      if (present_[seed]) r.d.push_back(seed, d_[seed]);
    return r;
  }

 private:
  double v_ = 0;
  std::vector<double> d_;
  std::vector<char> present_;  // seeds some term carried
};

// Value of either scalar type.
inline double value(double x) {
  return x;
}
inline double value(const Dual& x) {
  return x.v;
}

}  // namespace neurocloth::fuzzy
