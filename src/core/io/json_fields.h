#pragma once
// Typed, checked reads from a JSON document, every failure an InputError naming
// the file, the field and (via JsonLocator) its line. Every JSON input is read
// through it: scenes, material presets, scripts.
#include <nlohmann/json.hpp>

#include <initializer_list>
#include <string>

#include "core/base/vec3.h"
#include "core/io/input_error.h"
#include "core/io/json_locator.h"
#include "core/io/physical_limits.h"

namespace neurocloth {

class JsonFields {
 public:
  // Parses `text`; throws InputError with the parser's line and column on malformed JSON.
  JsonFields(const std::string& text, std::string file);

  const nlohmann::json& root() const { return root_; }
  const std::string& file() const { return file_; }

  [[noreturn]] void fail(const std::string& field, const std::string& message) const;

  // obj must be an object; each of its keys must be in `allowed`.
  void require_object(const nlohmann::json& obj, const std::string& field) const;
  void allow_only(const nlohmann::json& obj, const std::string& field,
                  std::initializer_list<const char*> allowed) const;

  // Member access: `field` names obj; the result names obj.key.
  bool has(const nlohmann::json& obj, const char* key) const { return obj.contains(key); }
  const nlohmann::json& member(const nlohmann::json& obj, const std::string& field,
                               const char* key) const;

  double number(const nlohmann::json& v, const std::string& field) const;
  int integer(const nlohmann::json& v, const std::string& field) const;
  bool boolean(const nlohmann::json& v, const std::string& field) const;
  std::string string(const nlohmann::json& v, const std::string& field) const;
  Vec3 vec3(const nlohmann::json& v, const std::string& field) const;
  // The same, inside a physical limit: the message gives the range and why.
  double number(const nlohmann::json& v, const std::string& field, const Limit& limit) const;
  int integer(const nlohmann::json& v, const std::string& field, const Limit& limit) const;
  Vec3 vec3(const nlohmann::json& v, const std::string& field, const Limit& limit) const;

 private:
  std::string text_;
  std::string file_;
  nlohmann::json root_;
  JsonLocator locator_;
};

}  // namespace neurocloth
