#include "fuzz/json_duplicate_keys.h"

#include <nlohmann/json.hpp>

#include <set>
#include <vector>

namespace neurocloth::fuzz {
namespace {

// Keeps the keys seen in each open object; SAX, so no tree and no recursion.
class DuplicateKeys : public nlohmann::json::json_sax_t {
 public:
  std::string duplicate;

  bool null() override { return true; }
  bool boolean(bool) override { return true; }
  bool number_integer(number_integer_t) override { return true; }
  bool number_unsigned(number_unsigned_t) override { return true; }
  bool number_float(number_float_t, const string_t&) override { return true; }
  bool string(string_t&) override { return true; }
  bool binary(binary_t&) override { return true; }
  bool start_object(std::size_t) override {
    open_.push_back({});
    return true;
  }
  bool key(string_t& k) override {
    if (!open_.back().insert(k).second) {
      duplicate = k;
      return false;  // stop at the first
    }
    return true;
  }
  bool end_object() override {
    open_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override { return true; }
  bool end_array() override { return true; }
  bool parse_error(std::size_t, const std::string&, const nlohmann::json::exception&) override {
    return false;
  }

 private:
  std::vector<std::set<std::string>> open_;
};

}  // namespace

std::string first_duplicate_key(const std::string& text) {
  DuplicateKeys keys;
  nlohmann::json::sax_parse(text, &keys, nlohmann::json::input_format_t::json, false);
  return keys.duplicate;
}

}  // namespace neurocloth::fuzz
