#pragma once
// The tokens of the Fuzzy Control Language (docs/fcl.md) and the cursor the
// reader walks them with. Private to src/core/fuzzy: fcl_reader.cpp parses
// them, and fcl_writer.cpp uses the same rules to refuse names that would not
// read back as one identifier.
#include <charconv>
#include <cmath>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "core/io/input_error.h"

namespace neurocloth::fuzzy::fcl {

enum class TokenKind { word, number, symbol, end, error };

struct Token {
  TokenKind kind = TokenKind::end;
  std::string text;  // as written; for an error token, what is wrong
  double value = 0;  // numbers only
  int line = 1, column = 1;
};

inline char upper(char c) {
  return c >= 'a' && c <= 'z' ? static_cast<char>(c - 'a' + 'A') : c;
}
inline bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
inline bool identifier_start(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
inline bool identifier_char(char c) {
  return identifier_start(c) || is_digit(c);
}

// Keywords are case-insensitive.
inline bool same_keyword(const std::string& word, const char* keyword) {
  std::size_t i = 0;
  for (; i < word.size() && keyword[i] != '\0'; ++i)
    if (upper(word[i]) != upper(keyword[i])) return false;
  return i == word.size() && keyword[i] == '\0';
}

// Words that would make a block or a rule ambiguous if they named a variable,
// term or block. Shape and method names are not here: they only appear where
// no name can.
inline bool is_reserved(const std::string& word) {
  static const char* const kReserved[] = {"FUNCTION_BLOCK",
                                          "END_FUNCTION_BLOCK",
                                          "VAR_INPUT",
                                          "VAR_OUTPUT",
                                          "END_VAR",
                                          "FUZZIFY",
                                          "END_FUZZIFY",
                                          "DEFUZZIFY",
                                          "END_DEFUZZIFY",
                                          "RULEBLOCK",
                                          "END_RULEBLOCK",
                                          "RANGE",
                                          "TERM",
                                          "METHOD",
                                          "DEFAULT",
                                          "NC",
                                          "ACT",
                                          "ACCU",
                                          "RULE",
                                          "IF",
                                          "THEN",
                                          "IS",
                                          "NOT",
                                          "AND",
                                          "OR",
                                          "WITH",
                                          "VERY",
                                          "SOMEWHAT"};
  for (const char* k : kReserved)
    if (same_keyword(word, k)) return true;
  return false;
}

inline bool is_identifier(const std::string& s) {
  if (s.empty() || !identifier_start(s[0])) return false;
  for (char c : s)
    if (!identifier_char(c)) return false;
  return !is_reserved(s);
}

// Splits FCL text into words, numbers and the symbols := : ; ( ) , .. |
// ('|' only in fuzzylite's "DEFAULT := 0 | NC")
// Comments are (* ... *) and // to the end of the line. The list ends with an
// `end` token, or with an `error` token at the first thing that is no token
// (the parser reports it with the element it was reading).
class Tokenizer {
 public:
  explicit Tokenizer(const std::string& text) : s_(text) {
    if (s_.compare(0, 3, "\xEF\xBB\xBF") == 0) i_ = line_start_ = 3;  // UTF-8 byte order mark
  }

  std::vector<Token> run() {
    std::vector<Token> out;
    for (;;) {
      out.push_back(next());
      if (out.back().kind == TokenKind::end || out.back().kind == TokenKind::error) return out;
    }
  }

 private:
  char at(std::size_t ahead) const { return i_ + ahead < s_.size() ? s_[i_ + ahead] : '\0'; }
  int column() const { return static_cast<int>(i_ - line_start_) + 1; }

  void advance() {
    if (s_[i_] == '\n') {
      ++line_;
      line_start_ = i_ + 1;
    }
    ++i_;
  }

  Token start(TokenKind kind) const {
    Token t;
    t.kind = kind;
    t.line = line_;
    t.column = column();
    return t;
  }

  static Token error(Token t, std::string message) {
    t.kind = TokenKind::error;
    t.text = std::move(message);
    return t;
  }

  // False (with `unclosed` set) when a (* comment never ends.
  bool skip_blank(Token& unclosed) {
    for (;;) {
      const char c = at(0);
      if (c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v') {
        advance();
      } else if (c == '/' && at(1) == '/') {
        while (i_ < s_.size() && s_[i_] != '\n')
          advance();
      } else if (c == '(' && at(1) == '*') {
        unclosed = start(TokenKind::error);
        advance();  // past "(*", so "(*)" does not close itself
        advance();
        while (i_ < s_.size() && !(at(0) == '*' && at(1) == ')'))
          advance();
        if (i_ >= s_.size()) return false;
        advance();
        advance();
      } else {
        return true;
      }
    }
  }

  Token next() {
    Token unclosed;
    if (!skip_blank(unclosed)) return error(unclosed, "comment '(*' is never closed by '*)'");
    Token t = start(TokenKind::end);
    if (i_ >= s_.size()) return t;
    const char c = at(0);
    if (identifier_start(c)) return word(t);
    const bool sign = c == '+' || c == '-';
    const char lead = sign ? at(1) : c;
    const char after = sign ? at(2) : at(1);
    if (is_digit(lead) || (lead == '.' && is_digit(after))) return number(t);
    for (const char* symbol : {":=", "..", ":", ";", "(", ")", ",", "|"}) {
      if (s_.compare(i_, std::char_traits<char>::length(symbol), symbol) != 0) continue;
      t.kind = TokenKind::symbol;
      t.text = symbol;
      for (std::size_t k = 0; k < t.text.size(); ++k)
        advance();
      return t;
    }
    const bool printable = c > ' ' && c < 127;
    return error(t, printable ? "unexpected character '" + std::string(1, c) + "'"
                              : "unexpected byte " + std::to_string(static_cast<unsigned char>(c)));
  }

  Token word(Token t) {
    const std::size_t from = i_;
    while (identifier_char(at(0)))
      advance();
    t.kind = TokenKind::word;
    t.text = s_.substr(from, i_ - from);
    return t;
  }

  void digits() {
    while (is_digit(at(0)))
      advance();
  }
  // A '.' that continues a number; ".." is the RANGE separator ("0..1").
  bool lone_dot() const { return at(0) == '.' && at(1) != '.'; }

  static constexpr double kMaxMagnitude = 1e15;

  Token number(Token t) {
    const std::size_t from = i_;
    if (at(0) == '+' || at(0) == '-') advance();
    digits();
    if (lone_dot()) {
      advance();
      digits();
    }
    const bool exponent_sign = (at(1) == '+' || at(1) == '-') && is_digit(at(2));
    if ((at(0) == 'e' || at(0) == 'E') && (is_digit(at(1)) || exponent_sign)) {
      advance();
      advance();
      digits();
    }
    // "1.2.3", "12kg", "1e": the number runs into more letters, digits or dots.
    const bool runs_on = identifier_char(at(0)) || lone_dot();
    while (identifier_char(at(0)) || lone_dot())
      advance();
    t.text = s_.substr(from, i_ - from);
    if (runs_on) return error(t, "bad number '" + t.text + "'");
    // from_chars ignores the locale, so "0.5" means the same everywhere.
    const char* first = t.text.data() + (t.text[0] == '+' ? 1 : 0);
    const auto result = std::from_chars(first, t.text.data() + t.text.size(), t.value);
    if (result.ec != std::errc() || result.ptr != t.text.data() + t.text.size())
      return error(t, "bad number '" + t.text + "': not representable as a double");
    // Ranges, set parameters and weights are multiplied and integrated over;
    // beyond this the engine's centroids would overflow to infinity.
    if (!(std::abs(t.value) <= kMaxMagnitude))
      return error(t, "number '" + t.text + "' is beyond +-1e15, more than a rule base can use");
    t.kind = TokenKind::number;
    return t;
  }

  const std::string& s_;
  std::size_t i_ = 0, line_start_ = 0;
  int line_ = 1;
};

struct Pos {
  int line = 0, column = 0;
};

inline Pos where(const Token& t) {
  return {t.line, t.column};
}

// Reads the tokens for the parser and throws the InputError for whatever it
// did not expect, naming the element being read (`field_`, kept up to date by
// the parser) and, at the end of the file, the block left open.
class Cursor {
 protected:
  Cursor(const std::string& text, std::string path)
      : tokens_(Tokenizer(text).run()), path_(std::move(path)) {}

  const Token& peek() const {
    const Token& t = tokens_[next_];
    if (t.kind == TokenKind::error) fail(t.text, where(t));
    return t;
  }
  Token take() {
    Token t = peek();
    if (t.kind != TokenKind::end) ++next_;
    return t;
  }
  bool at_keyword(const char* k) const {
    return peek().kind == TokenKind::word && same_keyword(peek().text, k);
  }
  bool at_symbol(const char* s) const {
    return peek().kind == TokenKind::symbol && peek().text == s;
  }
  bool at_name() const { return peek().kind == TokenKind::word && !is_reserved(peek().text); }
  bool accept_keyword(const char* k) { return at_keyword(k) ? (take(), true) : false; }
  bool accept_symbol(const char* s) { return at_symbol(s) ? (take(), true) : false; }

  Token expect_keyword(const char* k, const std::string& expected) {
    if (!at_keyword(k)) unexpected(expected);
    return take();
  }
  Token expect_symbol(const char* s, const std::string& expected) {
    if (!at_symbol(s)) unexpected(expected);
    return take();
  }
  Token expect_name(const std::string& expected) {
    if (!at_name()) unexpected(expected);
    return take();
  }
  double expect_number(const std::string& expected) {
    if (peek().kind != TokenKind::number) unexpected(expected);
    return take().value;
  }

  [[noreturn]] void fail(const std::string& message, Pos at) const {
    throw InputError(path_, field_, message, at.line, at.column);
  }

  // At the end of the file the culprit is the block left open, so the error
  // points at where that block began rather than at the last line.
  [[noreturn]] void unexpected(const std::string& expected) const {
    const Token& t = peek();
    if (t.kind == TokenKind::end && !open_.empty()) {
      const Open& b = open_.back();
      throw InputError(
          path_, b.field,
          "missing " + b.end + ": the file ends inside this block (expected " + expected + ")",
          b.at.line, b.at.column);
    }
    const std::string got = t.kind == TokenKind::end ? "end of file" : "'" + t.text + "'";
    fail("expected " + expected + ", got " + got, where(t));
  }

  // A block from its keyword to its END_ keyword; `field` names it in errors.
  void open(const Token& keyword, const std::string& field, const char* end) {
    open_.push_back({field, end, where(keyword)});
    field_ = field;
  }
  void close() {
    open_.pop_back();
    field_ = open_.empty() ? outer_field_ : open_.back().field;
  }

  std::string field_ = "FUNCTION_BLOCK";
  std::string outer_field_ = "FUNCTION_BLOCK";  // outside every block but FUNCTION_BLOCK

 private:
  struct Open {
    std::string field, end;
    Pos at;
  };
  std::vector<Token> tokens_;
  std::size_t next_ = 0;
  std::string path_;
  std::vector<Open> open_;
};

}  // namespace neurocloth::fuzzy::fcl
