#pragma once
// Where each value of a JSON document starts (line, column), so that an error
// about a field can name its line. nlohmann::json keeps no positions; this is a
// small second pass over text that nlohmann has already accepted as valid JSON.
// Fields are named like "cloth.grid.rows" and "cloth.pins[2][0]".
#include <map>
#include <set>
#include <string>
#include <utility>

namespace neurocloth {

class JsonLocator {
 public:
  explicit JsonLocator(const std::string& text);
  // {line, column}, 1-based; {0, 0} when the field is not in the text.
  std::pair<int, int> find(const std::string& field) const;

  // The first key written twice in one object (JSON leaves this undefined;
  // the parser would keep the last silently): its field and where the second
  // one stands. An empty field when every key is unique.
  struct Duplicate {
    std::string field;
    int line = 0, column = 0;
  };
  const Duplicate& duplicate() const { return duplicate_; }

  static std::string member(const std::string& parent, const std::string& key) {
    return parent.empty() ? key : parent + "." + key;
  }
  static std::string element(const std::string& parent, std::size_t index) {
    return parent + "[" + std::to_string(index) + "]";
  }

 private:
  void value(const std::string& field);
  void skip_space();
  std::string string_token();
  char peek() const { return pos_ < text_.size() ? text_[pos_] : '\0'; }
  void advance();

  const std::string& text_;
  std::size_t pos_ = 0;
  int line_ = 1, column_ = 1;
  std::map<std::string, std::pair<int, int>> where_;
  Duplicate duplicate_;
};

}  // namespace neurocloth
