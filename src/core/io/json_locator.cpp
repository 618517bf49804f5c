#include "core/io/json_locator.h"

#include <nlohmann/json.hpp>

#include <cctype>

namespace neurocloth {

JsonLocator::JsonLocator(const std::string& text) : text_(text) {
  // nlohmann skips a UTF-8 byte-order mark; so must we (it takes no column).
  if (text_.compare(0, 3, "\xEF\xBB\xBF") == 0) pos_ = 3;
  skip_space();
  if (pos_ < text_.size()) value("");
}

std::pair<int, int> JsonLocator::find(const std::string& field) const {
  const auto it = where_.find(field);
  return it == where_.end() ? std::pair<int, int>{0, 0} : it->second;
}

void JsonLocator::advance() {
  if (pos_ >= text_.size()) return;
  if (text_[pos_] == '\n') {
    ++line_;
    column_ = 1;
  } else {
    ++column_;
  }
  ++pos_;
}

void JsonLocator::skip_space() {
  while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_])))
    advance();
}

std::string JsonLocator::string_token() {
  // Skip to the closing quote, then let nlohmann decode the escapes (\uXXXX,
  // \t, ...) so that keys match the parsed document's keys exactly.
  const std::size_t start = pos_;
  advance();  // opening quote
  while (pos_ < text_.size() && peek() != '"') {
    if (peek() == '\\') advance();
    advance();
  }
  advance();  // closing quote
  try {
    return nlohmann::json::parse(text_.substr(start, pos_ - start)).get<std::string>();
  } catch (const nlohmann::json::exception&) {
    return {};  // unreachable for text nlohmann accepted
  }
}

void JsonLocator::value(const std::string& field) {
  where_[field] = {line_, column_};
  const char c = peek();
  if (c == '{') {
    advance();
    skip_space();
    std::set<std::string> keys;
    while (pos_ < text_.size() && peek() != '}') {
      const int key_line = line_, key_column = column_;
      const std::string key = string_token();
      if (!keys.insert(key).second && duplicate_.field.empty())
        duplicate_ = {member(field, key), key_line, key_column};
      skip_space();
      advance();  // ':'
      skip_space();
      value(member(field, key));
      skip_space();
      if (peek() == ',') advance();
      skip_space();
    }
    advance();
  } else if (c == '[') {
    advance();
    skip_space();
    std::size_t index = 0;
    while (pos_ < text_.size() && peek() != ']') {
      value(element(field, index++));
      skip_space();
      if (peek() == ',') advance();
      skip_space();
    }
    advance();
  } else if (c == '"') {
    string_token();
  } else {
    while (pos_ < text_.size() && !std::isspace(static_cast<unsigned char>(peek())) &&
           peek() != ',' && peek() != '}' && peek() != ']')
      advance();
  }
}

}  // namespace neurocloth
