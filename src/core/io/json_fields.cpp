#include "core/io/json_fields.h"

#include <cmath>

namespace neurocloth {
namespace {

// Scenes are a few levels deep; anything deeper than this is not a scene, and
// refusing it up front bounds the recursion of JsonLocator and of our readers.
constexpr int kMaxDepth = 64;

// Finds the first place nesting exceeds kMaxDepth (outside strings); {0, 0} if none.
std::pair<int, int> too_deep(const std::string& text) {
  int depth = 0, line = 1, column = 1;
  bool in_string = false, escaped = false;
  for (char c : text) {
    if (in_string) {
      if (escaped)
        escaped = false;
      else if (c == '\\')
        escaped = true;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxDepth) return {line, column};
    } else if (c == ']' || c == '}') {
      --depth;
    }
    if (c == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {0, 0};
}

nlohmann::json parse_or_throw(const std::string& text, const std::string& file) {
  const auto [deep_line, deep_column] = too_deep(text);
  if (deep_line > 0)
    throw InputError(file, "", "nested deeper than " + std::to_string(kMaxDepth) + " levels",
                     deep_line, deep_column);
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // nlohmann says "... at line L, column C: <what>"; keep the part after the position.
    const std::string what = e.what();
    const int line = number_after(what, "line "), column = number_after(what, "column ");
    const auto colon = what.find(": ", what.find("column"));
    const std::string detail = colon == std::string::npos ? what : what.substr(colon + 2);
    throw InputError(file, "", "malformed JSON: " + detail, line, column);
  } catch (const nlohmann::json::exception& e) {
    // e.g. out_of_range for a number too large for a double ("1e400"); no position given.
    const std::string what = e.what();
    const auto bracket = what.find("] ");
    throw InputError(
        file, "",
        "bad JSON value: " + (bracket == std::string::npos ? what : what.substr(bracket + 2)));
  }
}

const char* type_name(const nlohmann::json& v) {
  return v.type_name();
}

}  // namespace

JsonFields::JsonFields(const std::string& text, std::string file)
    : text_(text), file_(std::move(file)), root_(parse_or_throw(text_, file_)), locator_(text_) {
  const JsonLocator::Duplicate& d = locator_.duplicate();
  if (!d.field.empty())
    throw InputError(file_, d.field, "key written twice in one object (which one is meant?)",
                     d.line, d.column);
}

void JsonFields::fail(const std::string& field, const std::string& message) const {
  const auto [line, column] = locator_.find(field);
  throw InputError(file_, field, message, line, column);
}

void JsonFields::require_object(const nlohmann::json& obj, const std::string& field) const {
  if (!obj.is_object()) fail(field, std::string("expected an object, got ") + type_name(obj));
}

void JsonFields::allow_only(const nlohmann::json& obj, const std::string& field,
                            std::initializer_list<const char*> allowed) const {
  require_object(obj, field);
  for (const auto& item : obj.items()) {
    bool known = false;
    std::string list;
    for (const char* a : allowed) {
      known = known || item.key() == a;
      list += (list.empty() ? "" : ", ") + std::string(a);
    }
    if (!known)
      fail(JsonLocator::member(field, item.key()), "unknown key (expected one of: " + list + ")");
  }
}

const nlohmann::json& JsonFields::member(const nlohmann::json& obj, const std::string& field,
                                         const char* key) const {
  require_object(obj, field);
  if (!obj.contains(key)) {
    // A missing key has no line of its own: point at the object that lacks it.
    const auto [line, column] = locator_.find(field);
    throw InputError(file_, JsonLocator::member(field, key), "missing required key", line, column);
  }
  return obj.at(key);
}

double JsonFields::number(const nlohmann::json& v, const std::string& field) const {
  if (!v.is_number()) fail(field, std::string("expected a number, got ") + type_name(v));
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(field, "expected a finite number");
  return d;
}

int JsonFields::integer(const nlohmann::json& v, const std::string& field) const {
  if (!v.is_number_integer()) fail(field, std::string("expected an integer, got ") + type_name(v));
  if (v.is_number_unsigned() && v.get<unsigned long long>() > 2147483647ULL)
    fail(field, "integer out of range");
  const auto i = v.get<long long>();
  if (i < -2147483647LL || i > 2147483647LL) fail(field, "integer out of range");
  return static_cast<int>(i);
}

bool JsonFields::boolean(const nlohmann::json& v, const std::string& field) const {
  if (!v.is_boolean()) fail(field, std::string("expected true or false, got ") + type_name(v));
  return v.get<bool>();
}

std::string JsonFields::string(const nlohmann::json& v, const std::string& field) const {
  if (!v.is_string()) fail(field, std::string("expected a string, got ") + type_name(v));
  return v.get<std::string>();
}

double JsonFields::number(const nlohmann::json& v, const std::string& field,
                          const Limit& limit) const {
  const double d = number(v, field);
  if (!limit.contains(d)) fail(field, limit.refusal(d));
  return d;
}

int JsonFields::integer(const nlohmann::json& v, const std::string& field,
                        const Limit& limit) const {
  const int i = integer(v, field);
  if (!limit.contains(i)) fail(field, limit.refusal(i));
  return i;
}

Vec3 JsonFields::vec3(const nlohmann::json& v, const std::string& field, const Limit& limit) const {
  const Vec3 p = vec3(v, field);
  for (int k = 0; k < 3; ++k)
    if (!limit.contains(p[k])) fail(JsonLocator::element(field, k), limit.refusal(p[k]));
  return p;
}

Vec3 JsonFields::vec3(const nlohmann::json& v, const std::string& field) const {
  if (!v.is_array() || v.size() != 3) fail(field, "expected an array of 3 numbers [x, y, z]");
  return {number(v[0], JsonLocator::element(field, 0)),
          number(v[1], JsonLocator::element(field, 1)),
          number(v[2], JsonLocator::element(field, 2))};
}

}  // namespace neurocloth
