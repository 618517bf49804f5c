#include "core/fuzzy/term_degrees.h"

#include <algorithm>
#include <cstdio>

namespace neurocloth::fuzzy {

std::vector<TermDegree> term_degrees(const LinguisticVariable& variable, double x) {
  x = std::clamp(x, variable.min, variable.max);
  std::vector<TermDegree> out;
  for (const Term& t : variable.terms) {
    const double mu = t.function(x);
    if (mu > 0) out.push_back({t.name, std::min(mu, 1.0)});
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const TermDegree& a, const TermDegree& b) { return a.degree > b.degree; });
  return out;
}

std::string in_words(const LinguisticVariable& variable, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  std::string text = variable.name + " " + buf + ":";
  const std::vector<TermDegree> terms = term_degrees(variable, x);
  if (terms.empty()) return text + " no term";
  for (std::size_t i = 0; i < terms.size(); ++i) {
    std::snprintf(buf, sizeof buf, "%.2f", terms[i].degree);
    text += (i ? ", " : " ") + terms[i].term + " " + buf;
  }
  return text;
}

}  // namespace neurocloth::fuzzy
