#pragma once
// The one error type for bad input at a boundary (scene, OBJ, command line).
// It carries where the problem is so the message can name file, line and field.
#include <stdexcept>
#include <string>

namespace neurocloth {

class InputError : public std::runtime_error {
 public:
  // line/column are 1-based; 0 means "no line" (e.g. a missing key).
  InputError(std::string file, std::string field, std::string message, int line = 0,
             int column = 0);

  const std::string& file() const { return file_; }
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }
  int line() const { return line_; }
  int column() const { return column_; }

 private:
  std::string file_, field_, message_;
  int line_, column_;
};

// The number after the first occurrence of `word` in `text` ("line 12" -> 12),
// or 0. Parsers report positions inside their messages; this fishes them out.
int number_after(const std::string& text, const std::string& word);

}  // namespace neurocloth
