#include "core/io/input_error.h"

namespace neurocloth {
namespace {
std::string compose(const std::string& file, const std::string& field, const std::string& message,
                    int line, int column) {
  std::string s = file.empty() ? std::string("<input>") : file;
  if (line > 0) {
    s += ":" + std::to_string(line);
    if (column > 0) s += ":" + std::to_string(column);
  }
  s += ": ";
  if (!field.empty()) s += "field '" + field + "': ";
  return s + message;
}
}  // namespace

InputError::InputError(std::string file, std::string field, std::string message, int line,
                       int column)
    : std::runtime_error(compose(file, field, message, line, column)),
      file_(std::move(file)),
      field_(std::move(field)),
      message_(std::move(message)),
      line_(line),
      column_(column) {}

int number_after(const std::string& text, const std::string& word) {
  const auto at = text.find(word);
  if (at == std::string::npos) return 0;
  int n = 0;
  for (std::size_t i = at + word.size(); i < text.size() && text[i] >= '0' && text[i] <= '9'; ++i) {
    if (n > 100000000) return 0;
    n = n * 10 + (text[i] - '0');
  }
  return n;
}

}  // namespace neurocloth
