#include "core/base/cpu_features.h"

#include <cstdlib>
#include <string>
#include <vector>

namespace neurocloth {
namespace {

// The names in the variable's value, in order; separators are commas and
// white space. The value is bounded: a name list longer than this is an error.
constexpr std::size_t kMaxValueLength = 256;

std::vector<std::string> masked_names(const char* value) {
  std::vector<std::string> names;
  std::string name;
  for (const char* c = value; *c != '\0'; ++c) {
    if (*c == ',' || *c == ' ' || *c == '\t') {
      if (!name.empty()) names.push_back(name);
      name.clear();
    } else {
      name += *c;
    }
  }
  if (!name.empty()) names.push_back(name);
  return names;
}

const char* variable_value() {
  const char* v = std::getenv(kDisableCpuFeaturesVariable);
  return v == nullptr ? "" : v;
}

bool avx512_masked() {
  for (const std::string& name : masked_names(variable_value()))
    if (name == "avx512") return true;
  return false;
}

}  // namespace

bool cpu_reports_avx512() {
#if (defined(__x86_64__) || defined(__i386__)) && (defined(__GNUC__) || defined(__clang__))
  static const bool reports = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
  }();
  return reports;
#else
  return false;
#endif
}

bool cpu_has_avx512() {
  static const bool has = cpu_reports_avx512() && !avx512_masked();
  return has;
}

std::string disabled_cpu_features_error() {
  const std::string value = variable_value();
  if (value.size() > kMaxValueLength)
    return std::string(kDisableCpuFeaturesVariable) + " is " + std::to_string(value.size()) +
           " characters long; it takes a short list of feature names (" + kMaskableCpuFeatures +
           ")";
  for (const std::string& name : masked_names(value.c_str()))
    if (name != "avx512")
      return std::string(kDisableCpuFeaturesVariable) + ": unknown CPU feature '" + name +
             "' (known: " + kMaskableCpuFeatures + ")";
  return "";
}

}  // namespace neurocloth
