#include "core/io/json_writer.h"

#include <cmath>
#include <stdexcept>

#include "core/io/text_file.h"

namespace neurocloth {

std::optional<std::string> first_non_finite(const nlohmann::json& doc, const std::string& at) {
  if (doc.is_number_float() && !std::isfinite(doc.get<double>())) return at.empty() ? "(root)" : at;
  if (doc.is_object()) {
    for (const auto& item : doc.items())
      if (auto bad =
              first_non_finite(item.value(), at.empty() ? item.key() : at + "." + item.key()))
        return bad;
  } else if (doc.is_array()) {
    for (std::size_t i = 0; i < doc.size(); ++i)
      if (auto bad = first_non_finite(doc[i], at + "[" + std::to_string(i) + "]")) return bad;
  }
  return std::nullopt;
}

void write_json_atomically(const std::string& path, const nlohmann::json& doc) {
  // JSON has no NaN or Inf (the library would write null): a number a reader
  // expects must never turn into one. The simulation keeps its state finite,
  // so this refuses only a bug, before anything is written.
  if (const auto bad = first_non_finite(doc))
    throw std::runtime_error(path + ": not written: '" + *bad + "' is not a finite number");
  write_file_atomically(path, doc.dump(1) + "\n");
}

}  // namespace neurocloth
