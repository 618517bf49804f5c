#include "learn/rules/term_constraints.h"

#include <algorithm>
#include <cmath>

#include "core/io/physical_limits.h"

namespace neurocloth {
namespace {

using fuzzy::FuzzySystem;
using fuzzy::LinguisticVariable;
using fuzzy::MembershipFunction;
using fuzzy::Shape;

// Corners or centre (in order) and the width parameter (-1: none) of a shape.
void split_shape(const MembershipFunction& f, std::vector<int>& positions, int& width) {
  positions.clear();
  width = -1;
  switch (f.shape) {
    case Shape::triangle:
    case Shape::trapezoid:
      for (std::size_t k = 0; k < f.params.size(); ++k)
        positions.push_back(int(k));
      break;
    case Shape::points:
      for (std::size_t k = 0; k + 1 < f.params.size(); k += 2)
        positions.push_back(int(k));
      break;
    case Shape::gaussian:
      positions = {0};
      width = 1;
      break;
    case Shape::bell:
      positions = {2};
      width = 0;
      break;
    case Shape::sigmoid:
      positions = {1};
      break;
    case Shape::singleton:
    case Shape::linear:
      break;
  }
}

const LinguisticVariable& variable_of(const FuzzySystem& s, const TermRef& r) {
  return r.input ? s.inputs[r.variable] : s.outputs[r.variable];
}
MembershipFunction& function_of(FuzzySystem& s, const TermRef& r) {
  return (r.input ? s.inputs[r.variable] : s.outputs[r.variable]).terms[r.term].function;
}

std::string term_name(const FuzzySystem& s, const TermRef& r) {
  const LinguisticVariable& v = variable_of(s, r);
  return v.name + "." + v.terms[r.term].name;
}

// The nearest nondecreasing sequence (pool adjacent violators): the projection
// onto "in order" in the least-squares sense.
std::vector<double> in_order(const std::vector<double>& x) {
  std::vector<double> mean;
  std::vector<int> count;
  for (double v : x) {
    mean.push_back(v);
    count.push_back(1);
    while (mean.size() > 1 && mean[mean.size() - 2] > mean.back()) {
      const double m = mean.back();
      const int c = count.back();
      mean.pop_back();
      count.pop_back();
      mean.back() = (mean.back() * count.back() + m * c) / (count.back() + c);
      count.back() += c;
    }
  }
  std::vector<double> out;
  for (std::size_t b = 0; b < mean.size(); ++b)
    out.insert(out.end(), std::size_t(count[b]), mean[b]);
  return out;
}

}  // namespace

std::vector<int> tunable_indices(const MembershipFunction& f) {
  std::vector<int> positions;
  int width = -1;
  split_shape(f, positions, width);
  if (width >= 0) positions.push_back(width);
  std::sort(positions.begin(), positions.end());
  return positions;
}

double term_centre(const MembershipFunction& f) {
  const auto& p = f.params;
  switch (f.shape) {
    case Shape::triangle:
      return p[1];
    case Shape::trapezoid:
      return 0.5 * (p[1] + p[2]);
    case Shape::points: {
      double top = 0, sum = 0;
      int n = 0;
      for (std::size_t k = 0; k + 1 < p.size(); k += 2)
        top = std::max(top, p[k + 1]);
      for (std::size_t k = 0; k + 1 < p.size(); k += 2)
        if (p[k + 1] == top) sum += p[k], ++n;
      return n ? sum / n : 0;
    }
    case Shape::gaussian:
      return p[0];
    case Shape::bell:
      return p[2];
    case Shape::sigmoid:
      return p[1];
    case Shape::singleton:
    case Shape::linear:
      return p.empty() ? 0 : p[0];
  }
  return 0;
}

TermConstraints::TermConstraints(const FuzzySystem& start, const std::vector<TermRef>& tuned,
                                 double min_width_fraction) {
  for (const TermRef& r : tuned) {
    const LinguisticVariable& v = variable_of(start, r);
    const MembershipFunction& f = v.terms[r.term].function;
    Tuned t;
    t.ref = r;
    split_shape(f, t.positions, t.width);
    if (t.positions.empty()) continue;
    for (int k : t.positions) {
      t.lo.push_back(std::min(v.min, f.params[k]));
      t.hi.push_back(std::max(v.max, f.params[k]));
    }
    const double wanted = min_width_fraction * (v.max - v.min);
    const double now = t.width >= 0 ? std::abs(f.params[t.width])
                                    : f.params[t.positions.back()] - f.params[t.positions.front()];
    t.min_width = std::max(0.0, std::min(wanted, now));
    tuned_.push_back(t);

    auto same = [&](const Variable& x) { return x.input == r.input && x.index == r.variable; };
    if (std::none_of(variables_.begin(), variables_.end(), same)) {
      Variable var{r.input, r.variable, {}};
      for (std::size_t k = 0; k < v.terms.size(); ++k)
        if (!tunable_indices(v.terms[k].function).empty()) var.order.push_back(int(k));
      std::stable_sort(var.order.begin(), var.order.end(), [&](int a, int b) {
        return term_centre(v.terms[a].function) < term_centre(v.terms[b].function);
      });
      variables_.push_back(var);
    }
  }
}

bool TermConstraints::project_term(FuzzySystem& s, const Tuned& t,
                                   std::set<std::string>* active) const {
  MembershipFunction& f = function_of(s, t.ref);
  auto& p = f.params;
  const std::string name = term_name(s, t.ref);
  auto note = [&](const std::string& what) {
    if (active) active->insert(what);
  };
  bool changed = false;

  std::vector<double> x;
  for (int k : t.positions)
    x.push_back(p[k]);
  // Corners in order.
  const std::vector<double> ordered = in_order(x);
  for (std::size_t i = 0; i < x.size(); ++i)
    if (ordered[i] != x[i]) {
      changed = true;
      std::size_t j = i;
      while (j + 1 < x.size() && ordered[j + 1] == ordered[i])
        ++j;
      std::size_t first = i;
      while (first > 0 && ordered[first - 1] == ordered[i])
        --first;
      note(name + "[" + std::to_string(t.positions[first]) + "] = [" +
           std::to_string(t.positions[j]) + "] held in order (corners met)");
    }
  x = ordered;
  // No narrower than the minimum: widened about its middle, shifted back inside.
  if (t.width < 0 && x.size() > 1 && x.back() - x.front() < t.min_width) {
    const double mid = 0.5 * (x.front() + x.back());
    double a = mid - 0.5 * t.min_width, b = mid + 0.5 * t.min_width;
    if (b > t.hi.back()) a -= b - t.hi.back(), b = t.hi.back();
    if (a < t.lo.front()) b += t.lo.front() - a, a = t.lo.front();
    x.front() = a;
    x.back() = b;
    for (std::size_t i = 1; i + 1 < x.size(); ++i)
      x[i] = std::clamp(x[i], a, std::max(a, b));
    changed = true;
    note(name + " held at the minimum width " + show_number(t.min_width));
  }
  if (t.width >= 0 && std::abs(p[t.width]) < t.min_width) {
    p[t.width] = std::copysign(t.min_width, p[t.width] == 0 ? 1.0 : p[t.width]);
    changed = true;
    note(name + "[" + std::to_string(t.width) + "] held at the minimum width " +
         show_number(t.min_width));
  }
  // Inside the range (or where it started, when that was outside).
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double c = std::clamp(x[i], t.lo[i], t.hi[i]);
    if (c != x[i]) {
      const LinguisticVariable& v = variable_of(s, t.ref);
      const bool at_end = c == v.min || c == v.max;
      note(name + "[" + std::to_string(t.positions[i]) + "] held at " +
           (at_end ? "the range's end " : "its starting value (outside the RANGE) ") +
           show_number(c));
      x[i] = c;
    }
  }
  for (std::size_t i = 0; i < x.size(); ++i)
    if (p[t.positions[i]] != x[i]) {
      p[t.positions[i]] = x[i];
      changed = true;
    }
  return changed;
}

bool TermConstraints::keep_order(FuzzySystem& s, const Variable& v,
                                 std::set<std::string>* active) const {
  auto tuned_of = [&](int term) -> const Tuned* {
    for (const Tuned& t : tuned_)
      if (t.ref.input == v.input && t.ref.variable == v.index && t.ref.term == term) return &t;
    return nullptr;
  };
  auto shift = [&](const Tuned& t, double by) {
    auto& p = function_of(s, t.ref).params;
    for (int k : t.positions)
      p[k] += by;
  };
  bool changed = false;
  const LinguisticVariable& var = v.input ? s.inputs[v.index] : s.outputs[v.index];
  for (std::size_t i = 0; i + 1 < v.order.size(); ++i) {
    const int a = v.order[i], b = v.order[i + 1];
    const double ca = term_centre(var.terms[a].function), cb = term_centre(var.terms[b].function);
    if (!(ca > cb)) continue;
    const Tuned *ta = tuned_of(a), *tb = tuned_of(b);
    if (!ta && !tb) continue;
    const double gap = ca - cb;
    const double share = ta && tb ? 0.5 : 1.0;
    if (ta) shift(*ta, -share * gap);
    if (tb) shift(*tb, share * gap);
    changed = true;
    if (active)
      active->insert(var.name + "." + var.terms[a].name + " and " + var.terms[b].name +
                     " held in order (their centres met)");
  }
  return changed;
}

void TermConstraints::project(FuzzySystem& s, std::set<std::string>* active) const {
  // Each rule alone is a simple map; together they are applied until none acts
  // (a shift that keeps two centres in order can push a corner out of range).
  for (int pass = 0; pass < 50; ++pass) {
    bool changed = false;
    for (const Tuned& t : tuned_)
      changed = project_term(s, t, active) || changed;
    for (const Variable& v : variables_)
      changed = keep_order(s, v, active) || changed;
    if (!changed) return;
  }
  // Not settled: the corners' own rules, which matter most for a readable
  // and valid set, get the last word.
  for (const Tuned& t : tuned_)
    project_term(s, t, active);
}

}  // namespace neurocloth
