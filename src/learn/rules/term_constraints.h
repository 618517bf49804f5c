#pragma once
// What keeps a tuned rule base readable (docs/learning.md, "Tuning a rule base
// from examples"): for every tuned term,
//  - its corners in order (a triangle's a <= b <= c, a point list's x ascending),
//  - inside its variable's RANGE (a corner that starts outside, such as a
//    shoulder drawn past the range, may stay where it started but not go further),
//  - no narrower than a minimum width (a fraction of the range, or its starting
//    width if that is smaller), so no set collapses to a point,
//  - and the terms of a variable in the order of their centres (peak, plateau
//    middle, mean) as they started, so "small" stays left of "medium".
// project() maps any set of parameters onto these constraints (in place, on the
// tuned terms only); it is what the projected-gradient search applies after
// every step, and it can say, in words, which constraints it had to enforce.
#include <set>
#include <string>
#include <vector>

#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth {

// A term of an input (a membership function) or of a Mamdani output (a set).
struct TermRef {
  bool input = true;
  int variable = 0;
  int term = 0;
};

// The parameters of `f` the tuning moves: its corners or centre, and its width
// for the smooth shapes (a point list's degrees, a bell's slope and a sigmoid's
// gain stay). Empty for shapes it does not move (singleton, linear).
std::vector<int> tunable_indices(const fuzzy::MembershipFunction& f);

class TermConstraints {
 public:
  // `start` fixes the bounds, the minimum widths and the order of the centres.
  TermConstraints(const fuzzy::FuzzySystem& start, const std::vector<TermRef>& tuned,
                  double min_width_fraction);

  // Moves the tuned terms of `s` back inside the constraints. `active`, when not
  // null, collects one sentence per constraint that had to act
  // ("spring_constant.low[2] held at the range's end 200").
  void project(fuzzy::FuzzySystem& s, std::set<std::string>* active) const;

 private:
  struct Tuned {
    TermRef ref;
    std::vector<int> positions;  // parameter indices of corners or the centre, in order
    int width = -1;              // the width parameter of a gaussian or bell, else -1
    std::vector<double> lo, hi;  // per position: the range, widened to where it started
    double min_width = 0;        // corner span (or width parameter) at least this
  };
  struct Variable {
    bool input;
    int index;
    std::vector<int> order;  // the variable's terms by starting centre
  };

  bool project_term(fuzzy::FuzzySystem& s, const Tuned& t, std::set<std::string>* active) const;
  bool keep_order(fuzzy::FuzzySystem& s, const Variable& v, std::set<std::string>* active) const;

  std::vector<Tuned> tuned_;
  std::vector<Variable> variables_;
};

// A term's centre: a triangle's peak, a trapezoid's or point list's plateau
// middle, a gaussian's mean, a bell's or sigmoid's centre.
double term_centre(const fuzzy::MembershipFunction& f);

}  // namespace neurocloth
