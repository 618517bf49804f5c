#include "core/fuzzy/inference.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "core/fuzzy/dual.h"

namespace neurocloth::fuzzy {
namespace {

using std::max;
using std::min;

template <class T>
T tmin(const T& a, const T& b) {
  return b < a ? b : a;
}
template <class T>
T tmax(const T& a, const T& b) {
  return a < b ? b : a;
}
template <class T>
T tsqrt(const T& a) {
  using std::sqrt;
  return sqrt(a);
}

// A term's membership with a condition's or consequent's hedges (innermost
// first) and NOT applied.
template <class T>
T modified(T m, const std::vector<Hedge>& hedges, bool negated) {
  for (auto h = hedges.rbegin(); h != hedges.rend(); ++h)
    m = *h == Hedge::very ? m * m : tsqrt(m);
  return negated ? T(1.0) - m : m;
}

// Every tunable number of the system as T, laid out like parameters().
template <class T>
struct Params {
  std::vector<std::vector<std::vector<T>>> in, out;  // [var][term][k]
  std::vector<std::vector<T>> weight;                // [block][rule]
};

template <class T>
Params<T> constant_params(const FuzzySystem& s) {
  Params<T> p;
  for (const auto& v : s.inputs) {
    p.in.emplace_back();
    for (const auto& t : v.terms)
      p.in.back().emplace_back(t.function.params.begin(), t.function.params.end());
  }
  for (const auto& v : s.outputs) {
    p.out.emplace_back();
    for (const auto& t : v.terms)
      p.out.back().emplace_back(t.function.params.begin(), t.function.params.end());
  }
  for (const auto& b : s.blocks) {
    p.weight.emplace_back();
    for (const auto& r : b.rules)
      p.weight.back().push_back(T(r.weight));
  }
  return p;
}

template <class T>
T condition_degree(const Condition& c, const RuleBlock& block,
                   const std::vector<std::vector<T>>& mu) {
  switch (c.kind) {
    case Condition::Kind::term:
      return modified(mu[c.variable][c.term], c.hedges, c.negated);
    case Condition::Kind::negation:
      return T(1.0) - condition_degree(c.children[0], block, mu);
    case Condition::Kind::all: {
      T d = condition_degree(c.children[0], block, mu);
      for (std::size_t i = 1; i < c.children.size(); ++i) {
        const T e = condition_degree(c.children[i], block, mu);
        d = block.and_method == AndMethod::min ? tmin(d, e) : d * e;
      }
      return d;
    }
    case Condition::Kind::any: {
      T d = condition_degree(c.children[0], block, mu);
      for (std::size_t i = 1; i < c.children.size(); ++i) {
        const T e = condition_degree(c.children[i], block, mu);
        d = block.or_method == OrMethod::max ? tmax(d, e) : d + e - d * e;
      }
      return d;
    }
  }
  return T(0.0);
}

// One rule's share of one output: activation degree alpha of `term`, under the
// block's activation and accumulation methods.
template <class T>
struct Contribution {
  T alpha;
  int term;
  Activation act;
  Accumulation accu;
  const Consequent* consequent;  // its hedges and NOT
};

template <class T>
T implied(const Contribution<T>& c, const MembershipFunction& f, const std::vector<T>& p,
          const T& y) {
  const T m = modified(f.membership<T>(y, p.data()), c.consequent->hedges, c.consequent->negated);
  return c.act == Activation::min ? tmin(c.alpha, m) : c.alpha * m;
}

// A consequent's set at y, as a double (for locating the pieces).
template <class T>
double shaped(const Contribution<T>& c, const MembershipFunction& f, double y) {
  return modified(f(y), c.consequent->hedges, c.consequent->negated);
}

template <class T>
T aggregate(const std::vector<Contribution<T>>& cs, const LinguisticVariable& v,
            const std::vector<std::vector<T>>& p, const T& y) {
  const bool all_max = std::all_of(
      cs.begin(), cs.end(), [](const Contribution<T>& c) { return c.accu == Accumulation::max; });
  if (all_max) {
    // ACCU MAX keeps one implied set's value: find which on plain numbers (the
    // same values and comparisons as below), then evaluate only that one in T.
    // Same result and derivatives as taking the max in T over every set, but a
    // sampled centroid calls this 20001 times per output.
    int winner = -1;
    double best = 0.0;
    for (std::size_t i = 0; i < cs.size(); ++i) {
      const double alpha = value(cs[i].alpha);
      const double m = shaped(cs[i], v.terms[cs[i].term].function, value(y));
      const double implied = cs[i].act == Activation::min ? std::min(alpha, m) : alpha * m;
      if (best < implied) best = implied, winner = int(i);
    }
    if constexpr (std::is_same_v<T, double>) return best;
    if (winner < 0) return T(0.0);
    const Contribution<T>& c = cs[std::size_t(winner)];
    return implied(c, v.terms[c.term].function, p[c.term], y);
  }
  T a(0.0);
  for (const auto& c : cs) {
    const T m = implied(c, v.terms[c.term].function, p[c.term], y);
    a = c.accu == Accumulation::max ? tmax(a, m) : a + m;
  }
  return a;
}

// Values of f at the ends of [x0, x0 + h], extrapolated from its interior:
// exact when f is linear on the piece, even if it jumps at an end.
template <class F>
std::pair<double, double> piece_ends(double x0, double h, F&& f) {
  const double q1 = f(x0 + 0.25 * h), q3 = f(x0 + 0.75 * h);
  return {1.5 * q1 - 0.5 * q3, 1.5 * q3 - 0.5 * q1};
}

// Where d (linear on the piece, ends d0 and d1) changes sign inside it.
inline void add_crossing(double x0, double h, double d0, double d1, std::vector<double>& out) {
  if (d0 * d1 < 0) out.push_back(x0 + h * d0 / (d0 - d1));
}

// Sorted, unique, inside the range.
inline void tidy(std::vector<double>& pts, const LinguisticVariable& v) {
  for (double& x : pts)
    x = std::clamp(x, v.min, v.max);
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
}

// The points between which the accumulated set is linear: the sets' corners,
// then where a set crosses its activation level (ACT MIN), then — on pieces
// where every implied set is now linear — where two implied sets cross (ACCU
// MAX). Doubles: the positions carry no derivatives, and none are needed,
// because each piece is integrated from its interior.
template <class T>
std::vector<double> linear_pieces(const std::vector<Contribution<T>>& cs,
                                  const LinguisticVariable& v) {
  std::vector<double> pts = {v.min, v.max};
  for (const auto& c : cs)
    for (double b : v.terms[c.term].function.breakpoints())
      pts.push_back(b);
  tidy(pts, v);
  std::vector<double> extra;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const double x0 = pts[i], h = pts[i + 1] - x0;
    for (const auto& c : cs) {
      if (c.act != Activation::min) continue;
      const MembershipFunction& f = v.terms[c.term].function;
      const auto [f0, f1] = piece_ends(x0, h, [&](double y) { return shaped(c, f, y); });
      add_crossing(x0, h, f0 - value(c.alpha), f1 - value(c.alpha), extra);
    }
  }
  pts.insert(pts.end(), extra.begin(), extra.end());
  tidy(pts, v);
  if (cs.size() < 2) return pts;
  extra.clear();
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const double x0 = pts[i], h = pts[i + 1] - x0;
    std::vector<std::pair<double, double>> lines;
    for (const auto& c : cs) {
      const MembershipFunction& f = v.terms[c.term].function;
      const double alpha = value(c.alpha);
      lines.push_back(piece_ends(x0, h, [&](double y) {
        return c.act == Activation::min ? std::min(alpha, shaped(c, f, y))
                                        : alpha * shaped(c, f, y);
      }));
    }
    for (std::size_t a = 0; a < lines.size(); ++a)
      for (std::size_t b = a + 1; b < lines.size(); ++b)
        add_crossing(x0, h, lines[a].first - lines[b].first, lines[a].second - lines[b].second,
                     extra);
  }
  pts.insert(pts.end(), extra.begin(), extra.end());
  tidy(pts, v);
  return pts;
}

// sum of c * a over a centroid's samples (for duals, DualSum in dual.h).
template <class T>
class WeightedSum {
 public:
  void add(double c, const T& a) { total_ += c * a; }
  T total() const { return total_; }

 private:
  T total_ = 0.0;
};
template <>
class WeightedSum<Dual> : public DualSum {};

// (integral of mu, integral of y mu) over the output's range.
template <class T>
std::pair<T, T> moments(const std::vector<Contribution<T>>& cs, const LinguisticVariable& v,
                        const std::vector<std::vector<T>>& p) {
  bool exact = true;
  for (const auto& c : cs)
    exact = exact && v.terms[c.term].function.piecewise_linear() && c.consequent->hedges.empty();
  T area(0.0), moment(0.0);
  if (exact) {
    // Linear on each piece: two interior samples give the line; integrate it.
    const std::vector<double> pts = linear_pieces(cs, v);
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      const double x0 = pts[i], x1 = pts[i + 1], h = x1 - x0;
      if (!(h > 0)) continue;
      const T q1 = aggregate(cs, v, p, T(x0 + 0.25 * h)),
              q3 = aggregate(cs, v, p, T(x0 + 0.75 * h));
      const T a0 = T(1.5) * q1 - T(0.5) * q3, a1 = T(1.5) * q3 - T(0.5) * q1;
      area += T(0.5 * h) * (a0 + a1);
      moment += T(h / 6.0) * (T(x0) * (T(2.0) * a0 + a1) + T(x1) * (a0 + T(2.0) * a1));
    }
    return {area, moment};
  }
  const double h = (v.max - v.min) / kCentroidSamples;
  WeightedSum<T> sampled_area, sampled_moment;
  for (int i = 0; i <= kCentroidSamples; ++i) {
    const double y = i == kCentroidSamples ? v.max : v.min + i * h;
    const double w = (i == 0 || i == kCentroidSamples) ? 0.5 * h : h;
    const T a = aggregate(cs, v, p, T(y));
    sampled_area.add(w, a);
    sampled_moment.add(w * y, a);
  }
  return {sampled_area.total(), sampled_moment.total()};
}

// Takagi-Sugeno: activations (accumulated per term) weighting each term's value.
template <class T>
std::pair<T, T> weighted_sum(const std::vector<Contribution<T>>& cs, const LinguisticVariable& v,
                             const std::vector<std::vector<T>>& p, const std::vector<T>& x) {
  std::vector<T> alpha(v.terms.size(), T(0.0));
  for (const auto& c : cs)
    alpha[c.term] =
        c.accu == Accumulation::max ? tmax(alpha[c.term], c.alpha) : alpha[c.term] + c.alpha;
  T num(0.0), den(0.0);
  for (std::size_t t = 0; t < v.terms.size(); ++t) {
    if (!(value(alpha[t]) > 0)) continue;
    const auto& pt = p[t];
    T z = pt[0];
    if (v.terms[t].function.shape == Shape::linear)
      for (std::size_t i = 0; i < x.size() && i + 1 < pt.size(); ++i)
        z += pt[i + 1] * x[i];
    num += alpha[t] * z;
    den += alpha[t];
  }
  return {num, den};
}

template <class T>
std::vector<T> run(const FuzzySystem& s, const std::vector<T>& raw_inputs, const Params<T>& p,
                   InferenceReport& report) {
  report = {};
  std::vector<T> x;
  std::vector<std::vector<T>> mu;
  for (std::size_t i = 0; i < s.inputs.size(); ++i) {
    const LinguisticVariable& v = s.inputs[i];
    const double raw = value(raw_inputs[i]);
    const bool out = raw < v.min || raw > v.max;
    report.clamped.push_back(out);
    if (out) {
      std::ostringstream os;
      os << "input '" << v.name << "' = " << raw << " is outside its range [" << v.min << ", "
         << v.max << "]; clamped to " << std::clamp(raw, v.min, v.max);
      report.notes.push_back(os.str());
    }
    x.push_back(raw < v.min ? T(v.min) : raw > v.max ? T(v.max) : raw_inputs[i]);
    mu.emplace_back();
    for (std::size_t t = 0; t < v.terms.size(); ++t)
      mu.back().push_back(v.terms[t].function.membership<T>(x.back(), p.in[i][t].data()));
  }

  std::vector<std::vector<Contribution<T>>> contributions(s.outputs.size());
  for (std::size_t b = 0; b < s.blocks.size(); ++b) {
    const RuleBlock& block = s.blocks[b];
    report.activation.emplace_back();
    for (std::size_t r = 0; r < block.rules.size(); ++r) {
      const Rule& rule = block.rules[r];
      const T alpha = p.weight[b][r] * condition_degree(rule.condition, block, mu);
      report.activation.back().push_back(value(alpha));
      for (const Consequent& c : rule.consequents)
        contributions[c.variable].push_back(
            {alpha, c.term, block.activation, block.accumulation, &c});
    }
  }

  std::vector<T> y;
  for (std::size_t o = 0; o < s.outputs.size(); ++o) {
    const LinguisticVariable& v = s.outputs[o];
    const auto [num, den] = v.method == Defuzzification::centroid
                                ? [&] { auto m = moments(contributions[o], v, p.out[o]); return std::pair<T, T>{m.second, m.first}; }()
                                : weighted_sum(contributions[o], v, p.out[o], x);
    const bool fired = value(den) > 0;
    report.defaulted.push_back(!fired);
    if (fired) {
      y.push_back(num / den);
    } else {
      const double fallback = std::isnan(v.default_value) ? 0.5 * (v.min + v.max) : v.default_value;
      std::ostringstream os;
      os << "no rule fired for output '" << v.name << "'; kept its "
         << (std::isnan(v.default_value) ? "range midpoint " : "DEFAULT ") << fallback;
      report.notes.push_back(os.str());
      y.push_back(T(fallback));
    }
    report.outputs.push_back(value(y.back()));
  }
  return y;
}

// Where parameter q lives in p; null when the system has no such parameter.
template <class T>
T* slot(Params<T>& p, const Parameter& q) {
  auto at = [](auto& v, int i) { return i >= 0 && std::size_t(i) < v.size() ? &v[i] : nullptr; };
  switch (q.kind) {
    case Parameter::Kind::input_term:
    case Parameter::Kind::output_term: {
      auto* var = at(q.kind == Parameter::Kind::input_term ? p.in : p.out, q.variable);
      auto* term = var ? at(*var, q.term) : nullptr;
      return term ? at(*term, q.index) : nullptr;
    }
    case Parameter::Kind::rule_weight: {
      auto* block = at(p.weight, q.variable);
      return block ? at(*block, q.term) : nullptr;
    }
  }
  return nullptr;
}

}  // namespace

InferenceReport infer(const FuzzySystem& s, const std::vector<double>& inputs) {
  if (inputs.size() != s.inputs.size())
    throw std::invalid_argument("expected " + std::to_string(s.inputs.size()) + " inputs, got " +
                                std::to_string(inputs.size()));
  InferenceReport report;
  run<double>(s, inputs, constant_params<double>(s), report);
  return report;
}

std::vector<Parameter> parameters(const FuzzySystem& s) {
  std::vector<Parameter> ps;
  auto add_terms = [&](const std::vector<LinguisticVariable>& vars, Parameter::Kind kind) {
    for (std::size_t v = 0; v < vars.size(); ++v)
      for (std::size_t t = 0; t < vars[v].terms.size(); ++t)
        for (std::size_t k = 0; k < vars[v].terms[t].function.params.size(); ++k)
          ps.push_back(
              {kind, static_cast<int>(v), static_cast<int>(t), static_cast<int>(k),
               vars[v].name + "." + vars[v].terms[t].name + "[" + std::to_string(k) + "]"});
  };
  add_terms(s.inputs, Parameter::Kind::input_term);
  add_terms(s.outputs, Parameter::Kind::output_term);
  for (std::size_t b = 0; b < s.blocks.size(); ++b)
    for (std::size_t r = 0; r < s.blocks[b].rules.size(); ++r)
      ps.push_back({Parameter::Kind::rule_weight, static_cast<int>(b), static_cast<int>(r), 0,
                    s.blocks[b].name + "/RULE " + s.blocks[b].rules[r].label + ".weight"});
  return ps;
}

double get_parameter(const FuzzySystem& s, const Parameter& p) {
  switch (p.kind) {
    case Parameter::Kind::input_term:
      return s.inputs[p.variable].terms[p.term].function.params[p.index];
    case Parameter::Kind::output_term:
      return s.outputs[p.variable].terms[p.term].function.params[p.index];
    case Parameter::Kind::rule_weight:
      return s.blocks[p.variable].rules[p.term].weight;
  }
  return 0;
}

void set_parameter(FuzzySystem& s, const Parameter& p, double value) {
  switch (p.kind) {
    case Parameter::Kind::input_term:
      s.inputs[p.variable].terms[p.term].function.params[p.index] = value;
      break;
    case Parameter::Kind::output_term:
      s.outputs[p.variable].terms[p.term].function.params[p.index] = value;
      break;
    case Parameter::Kind::rule_weight:
      s.blocks[p.variable].rules[p.term].weight = value;
      break;
  }
}

InferenceGradient infer_gradient(const FuzzySystem& s, const std::vector<double>& inputs) {
  return infer_gradient(s, inputs, parameters(s));
}

InferenceGradient infer_gradient(const FuzzySystem& s, const std::vector<double>& inputs,
                                 const std::vector<Parameter>& wrt) {
  if (inputs.size() != s.inputs.size())
    throw std::invalid_argument("expected " + std::to_string(s.inputs.size()) + " inputs, got " +
                                std::to_string(inputs.size()));
  InferenceGradient g;
  g.parameters = wrt;
  // Seeds: the inputs, then wrt in its order.
  const std::size_t ni = inputs.size(), np = wrt.size();
  std::vector<Dual> x;
  for (std::size_t i = 0; i < ni; ++i)
    x.emplace_back(inputs[i], std::uint32_t(i));
  Params<Dual> p = constant_params<Dual>(s);
  for (std::size_t k = 0; k < np; ++k) {
    const Parameter& q = wrt[k];
    Dual* d = slot(p, q);
    if (!d) throw std::invalid_argument("no parameter " + q.name + " in " + s.name);
    if (!d->d.empty()) throw std::invalid_argument("parameter " + q.name + " asked for twice");
    *d = Dual(d->v, std::uint32_t(ni + k));
  }
  const std::vector<Dual> y = run<Dual>(s, x, p, g.report);
  g.d_inputs.setZero(Eigen::Index(y.size()), Eigen::Index(ni));
  g.d_parameters.setZero(Eigen::Index(y.size()), Eigen::Index(np));
  for (std::size_t o = 0; o < y.size(); ++o)
    for (const auto& e : y[o].d) {
      if (e.seed < ni)
        g.d_inputs(Eigen::Index(o), Eigen::Index(e.seed)) = e.d;
      else
        g.d_parameters(Eigen::Index(o), Eigen::Index(e.seed - ni)) = e.d;
    }
  return g;
}

}  // namespace neurocloth::fuzzy
