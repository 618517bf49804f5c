#include "core/fuzzy/membership_function.h"

#include <algorithm>
#include <cmath>

#include "core/fuzzy/dual.h"
#include "core/fuzzy/fuzzy_rule.h"

namespace neurocloth::fuzzy {

const char* to_string(Shape s) {
  switch (s) {
    case Shape::points:
      return "points";
    case Shape::triangle:
      return "trian";
    case Shape::trapezoid:
      return "trape";
    case Shape::gaussian:
      return "gauss";
    case Shape::bell:
      return "gbell";
    case Shape::sigmoid:
      return "sigm";
    case Shape::singleton:
      return "singleton";
    case Shape::linear:
      return "linear";
  }
  return "?";
}

const char* to_string(Hedge h) {
  return h == Hedge::very ? "very" : "somewhat";
}

int parameter_count(Shape s) {
  switch (s) {
    case Shape::triangle:
      return 3;
    case Shape::trapezoid:
      return 4;
    case Shape::gaussian:
      return 2;
    case Shape::bell:
      return 3;
    case Shape::sigmoid:
      return 2;
    case Shape::singleton:
      return 1;
    case Shape::points:
    case Shape::linear:
      return -1;
  }
  return -1;
}

std::vector<double> MembershipFunction::breakpoints() const {
  switch (shape) {
    case Shape::triangle:
    case Shape::trapezoid:
      return params;
    case Shape::points: {
      std::vector<double> xs;
      for (std::size_t i = 0; i + 1 < params.size(); i += 2)
        xs.push_back(params[i]);
      return xs;
    }
    default:
      return {};
  }
}

std::vector<double> MembershipFunction::axis_positions() const {
  const auto& p = params;
  if (shape == Shape::points) return breakpoints();
  if (shape == Shape::gaussian) return {p[0]};  // mean
  if (shape == Shape::bell) return {p[2]};      // centre c
  if (shape == Shape::sigmoid) return {p[1]};   // centre
  if (shape == Shape::linear) return {};
  return p;  // trian, trape, singleton: every parameter
}

std::string MembershipFunction::validate() const {
  const int n = parameter_count(shape);
  if (n >= 0 && static_cast<int>(params.size()) != n)
    return std::string(to_string(shape)) + " takes " + std::to_string(n) + " parameters, got " +
           std::to_string(params.size());
  for (double p : params)
    if (!std::isfinite(p)) return "parameters must be finite";
  switch (shape) {
    case Shape::points:
      if (params.size() < 2 || params.size() % 2) return "a point list needs (x, y) pairs";
      if (params.size() / 2 > kMaxPoints)
        return "a point list holds at most " + std::to_string(kMaxPoints) + " points, got " +
               std::to_string(params.size() / 2);
      for (std::size_t i = 0; i + 1 < params.size(); i += 2) {
        if (params[i + 1] < 0 || params[i + 1] > 1) return "membership degrees must be in [0, 1]";
        if (i >= 2 && params[i] < params[i - 2]) return "point x values must not decrease";
      }
      return {};
    case Shape::triangle:
      return params[0] <= params[1] && params[1] <= params[2] ? "" : "trian needs a <= b <= c";
    case Shape::trapezoid:
      return params[0] <= params[1] && params[1] <= params[2] && params[2] <= params[3]
                 ? ""
                 : "trape needs a <= b <= c <= d";
    case Shape::gaussian:
      return params[1] > 0 ? "" : "gauss needs sigma > 0";
    case Shape::bell:
      return params[0] != 0 && params[1] > 0 ? "" : "gbell needs a != 0 and b > 0";
    case Shape::linear:
      return params.empty() ? "linear needs at least a constant" : "";
    default:
      return {};
  }
}

MembershipFunction ramp(double start, double end) {
  if (start < end) return {Shape::points, {start, 0, end, 1}};
  return {Shape::points, {end, 1, start, 0}};
}

namespace {

// Rising edge 0 at a to 1 at b; a vertical edge (a == b) is a step at a.
template <class T>
T rise(const T& x, const T& a, const T& b) {
  if (x <= a) return T(0.0);
  if (x >= b) return T(1.0);
  return (x - a) / (b - a);
}
template <class T>
T fall(const T& x, const T& c, const T& d) {
  if (x <= c) return T(1.0);
  if (x >= d) return T(0.0);
  return (d - x) / (d - c);
}

}  // namespace

template <class T>
T MembershipFunction::membership(const T& x, const T* p) const {
  using std::abs;
  using std::exp;
  using std::pow;
  switch (shape) {
    case Shape::triangle: {
      if (x < p[1]) return rise(x, p[0], p[1]);
      return fall(x, p[1], p[2]);
    }
    case Shape::trapezoid: {
      if (x < p[1]) return rise(x, p[0], p[1]);
      if (x <= p[2]) return T(1.0);
      return fall(x, p[2], p[3]);
    }
    case Shape::points: {
      const std::size_t n = params.size() / 2;
      if (x <= p[0]) return p[1];
      for (std::size_t i = 1; i < n; ++i) {
        const T& x0 = p[2 * i - 2];
        const T& x1 = p[2 * i];
        if (x <= x1) {
          if (!(x1 > x0)) return p[2 * i + 1];
          return p[2 * i - 1] + (p[2 * i + 1] - p[2 * i - 1]) * ((x - x0) / (x1 - x0));
        }
      }
      return p[2 * n - 1];
    }
    case Shape::gaussian: {
      const T z = (x - p[0]) / p[1];
      return exp(T(-0.5) * z * z);
    }
    case Shape::bell: {
      const T z = abs((x - p[2]) / p[0]);
      return T(1.0) / (T(1.0) + pow(z, T(2.0) * p[1]));
    }
    case Shape::sigmoid:
      return T(1.0) / (T(1.0) + exp(-(p[0] * (x - p[1]))));
    case Shape::singleton:
      return value(x) == value(p[0]) ? T(1.0) : T(0.0);
    case Shape::linear:
      return T(0.0);  // not a membership function (see inference)
  }
  return T(0.0);
}

template double MembershipFunction::membership<double>(const double&, const double*) const;
template Dual MembershipFunction::membership<Dual>(const Dual&, const Dual*) const;

}  // namespace neurocloth::fuzzy
