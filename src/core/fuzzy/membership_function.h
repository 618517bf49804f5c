#pragma once
// A linguistic term's membership function mu(x) in [0, 1] (or, for a
// Takagi-Sugeno output, its consequent function). Written once over the scalar
// type T so that inference and its derivatives share the code (see dual.h).
#include <cstddef>
#include <string>
#include <vector>

namespace neurocloth::fuzzy {

enum class Shape {
  points,  // x0 y0 x1 y1 ... : piecewise linear through the points (x ascending), constant outside
  triangle,   // a b c           : 0 at a, 1 at b, 0 at c
  trapezoid,  // a b c d         : 0 at a, 1 on [b, c], 0 at d
  gaussian,   // mean sigma      : exp(-(x - mean)^2 / (2 sigma^2))
  bell,       // a b c           : 1 / (1 + |(x - c) / a|^(2b))
  sigmoid,    // gain center     : 1 / (1 + exp(-gain (x - center)))
  singleton,  // value           : 1 at x = value (outputs: a Sugeno constant)
  linear,     // c0 c1 .. cn     : Sugeno consequent c0 + sum_i c_i * input_i (outputs only)
};

// The most points a point list may hold: far above what a person or a tool
// writes (fuzzylite's Discrete terms have tens), far below what would slow
// every inference down. validate() refuses more, so every reader does.
inline constexpr std::size_t kMaxPoints = 10000;

const char* to_string(Shape s);
// Number of parameters a shape takes; -1 for points and linear (variable).
int parameter_count(Shape s);

struct MembershipFunction {
  Shape shape = Shape::triangle;
  std::vector<double> params;

  // True for shapes whose aggregate output can be integrated exactly.
  bool piecewise_linear() const {
    return shape == Shape::points || shape == Shape::triangle || shape == Shape::trapezoid;
  }
  // x positions where the slope of a piecewise-linear shape changes.
  std::vector<double> breakpoints() const;
  // The parameters that are positions on the variable's axis: what rule-file
  // readers check against the RANGE and infer a missing RANGE from.
  std::vector<double> axis_positions() const;
  // Empty when valid; otherwise what is wrong (e.g. "triangle needs a <= b <= c").
  std::string validate() const;

  double operator()(double x) const { return membership<double>(x, params.data()); }

  // mu(x) with parameters p (params() converted to T by the caller).
  template <class T>
  T membership(const T& x, const T* p) const;
};

// fuzzylite's Ramp (FCL "Ramp start end", .fis 'rampmf',[start end]): 0 at
// start, 1 at end, as the point list it draws. The caller refuses start == end.
MembershipFunction ramp(double start, double end);

}  // namespace neurocloth::fuzzy
