#pragma once
// A forward-mode dual number: a value and its derivatives with respect to a
// fixed set of seeds. The fuzzy engine is written once over a scalar type T and
// run with T = double to infer, or T = Dual to get exact derivatives of every
// output with respect to the inputs, the membership-function parameters and the
// consequents in the same pass (what tuning the rule base by gradient needs).
#include <algorithm>
#include <cmath>
#include <vector>

namespace neurocloth::fuzzy {

struct Dual {
  double v = 0;
  std::vector<double> d;  // empty means "all zero" (a constant)

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: constants convert implicitly
  Dual(double value, std::size_t seeds, std::size_t seed) : v(value), d(seeds, 0.0) {
    d[seed] = 1.0;
  }

  double derivative(std::size_t i) const { return i < d.size() ? d[i] : 0.0; }
};

namespace detail {
// r.d = a * x.d + b * y.d, treating empty as zero.
inline std::vector<double> combine(double a, const std::vector<double>& x, double b,
                                   const std::vector<double>& y) {
  const std::size_t n = std::max(x.size(), y.size());
  std::vector<double> r(n, 0.0);
  for (std::size_t i = 0; i < x.size(); ++i)
    r[i] += a * x[i];
  for (std::size_t i = 0; i < y.size(); ++i)
    r[i] += b * y[i];
  return r;
}
inline std::vector<double> scale(double a, const std::vector<double>& x) {
  std::vector<double> r(x.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    r[i] = a * x[i];
  return r;
}
}  // namespace detail

inline Dual make(double v, std::vector<double> d) {
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

// Value of either scalar type.
inline double value(double x) {
  return x;
}
inline double value(const Dual& x) {
  return x.v;
}

}  // namespace neurocloth::fuzzy
