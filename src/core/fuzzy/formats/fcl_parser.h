#pragma once
// The FCL parser's class, private to src/core/fuzzy. Its definitions are split
// by what they read: fcl_reader.cpp the function block, declarations and the
// FUZZIFY / DEFUZZIFY blocks; fcl_rule_parser.cpp the RULEBLOCKs and their rules.
#include <array>
#include <cstdio>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "core/fuzzy/formats/fcl_lexer.h"
#include "core/fuzzy/fuzzy_system.h"

namespace neurocloth::fuzzy::fcl {

inline std::string show(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// "a, b, c" from variables or terms.
template <class T>
std::string names(const std::vector<T>& list) {
  std::string s;
  for (const T& item : list)
    s += (s.empty() ? "" : ", ") + item.name;
  return s.empty() ? "none" : s;
}

// A FUZZIFY or DEFUZZIFY block while it is read.
struct VariableBlock {
  LinguisticVariable variable;
  bool output = false;
  std::string field;  // "FUZZIFY mass"
  Pos at;             // the variable's name
  std::vector<Pos> term_at;
  bool has_range = false, has_method = false, has_default = false;
  Pos method_at;
  // fuzzylite: ACCU inside DEFUZZIFY (NONE: each rule on its own) and LOCK : RANGE.
  bool has_accu = false, accu_none = false, lock_range = false;
  Accumulation accu = Accumulation::max;
  Pos accu_at, lock_at;
};

// What a DEFUZZIFY block said about accumulation, kept until the rule blocks
// are read (fcl_dialect.cpp, resolve_accumulation).
struct OutputNote {
  bool has_accu = false;
  Accumulation accu = Accumulation::max;
  Pos at;  // its ACCU, or its name when it has none
};

struct BlockNote {
  bool has_accu = false;
  std::string field;  // "RULEBLOCK name"
};

// Where a declared variable was declared and (once read) defined.
struct Slot {
  Pos declared, defined;
  bool has_block = false;
};

// Reads in one pass, in the order IEC 61131-7 prescribes: every VAR section
// before the FUZZIFY / DEFUZZIFY blocks (in any order among themselves), and
// those before the RULEBLOCKs. So every name is known when it is used and
// errors come in file order.
class Parser : Cursor {
 public:
  Parser(const std::string& text, const std::string& path) : Cursor(text, path) {}

  FuzzySystem parse() {
    function_block();
    return std::move(system_);
  }

 private:
  enum class Part { declarations, variables, rules };

  // fcl_reader.cpp: FUNCTION_BLOCK, VAR, FUZZIFY and DEFUZZIFY.
  void function_block();
  void enter(Part next, const Token& head);
  void declarations(bool input);
  void variable_block(bool output);
  Slot& declared_slot(const VariableBlock& b);
  void range(VariableBlock& b);
  void term(VariableBlock& b);
  MembershipFunction membership(const VariableBlock& b);
  MembershipFunction points();
  MembershipFunction linear(const VariableBlock& b, const Token& head);
  void method(VariableBlock& b);
  void default_value(VariableBlock& b);
  void finish(VariableBlock& b);
  void infer_range(VariableBlock& b);
  void check_method(const VariableBlock& b);

  // fcl_dialect.cpp: other tools' names and statements.
  int norm(int which, bool none_allowed = false);  // 0/1: the setting's methods; -1: NONE
  Defuzzification defuzzifier();
  MembershipFunction foreign_term(const std::string& expected);
  void height(const Token& head);
  MembershipFunction foreign_linear(const Token& head, double first);
  MembershipFunction discrete(const Token& head);
  MembershipFunction ramp(const Token& head);
  void enabled();
  void lock(VariableBlock& b);
  void output_accumulation(VariableBlock& b);
  void check_pairing(const RuleBlock& rb, const std::array<bool, 4>& given);
  void resolve_accumulation();

  // fcl_rule_parser.cpp: RULEBLOCK and its rules.
  void rule_block();
  bool setting(RuleBlock& rb, std::array<bool, 4>& given);
  Rule rule(const RuleBlock& rb);
  // OR of ANDs: AND binds tighter. A chain "a AND b AND c" is one node; a
  // parenthesised group stays its own node, so the tree is exactly as written.
  Condition disjunction() { return chain(Condition::Kind::any, "OR"); }
  Condition conjunction() { return chain(Condition::Kind::all, "AND"); }
  Condition chain(Condition::Kind kind, const char* connective);
  Condition unary();
  Condition nested();
  Condition clause();
  Consequent consequent();
  std::pair<int, int> lookup(const Token& variable, const Token& term, bool output);

  static std::string first_at(Pos p) {
    return " (the first is at line " + std::to_string(p.line) + ")";
  }

  // For items a block may hold only once.
  void once(bool& given, const Token& head) {
    if (std::exchange(given, true)) fail(head.text + " given twice", where(head));
  }

  // Each '(' and NOT nests one level, here and again in inference and in the
  // writer, which all recurse: a hostile file could nest until the stack runs
  // out. No rule a person writes comes near this depth.
  static constexpr int kMaxConditionDepth = 32;

  Part part_ = Part::declarations;
  int depth_ = 0;                                 // of the condition being read
  std::vector<Slot> input_slots_, output_slots_;  // parallel to system_.inputs / outputs
  FuzzySystem system_;
  std::vector<OutputNote> output_notes_;  // parallel to system_.outputs
  std::vector<BlockNote> block_notes_;    // parallel to system_.blocks
  std::array<Pos, 4> setting_at_{};       // AND, OR, ACT, ACCU of the block being read
  bool unterminated_rules_ = false;       // a RULE without ';' (fuzzylite)
};

}  // namespace neurocloth::fuzzy::fcl
