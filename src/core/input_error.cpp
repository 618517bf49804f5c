#include "input_error.h"

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

}  // namespace neurocloth
