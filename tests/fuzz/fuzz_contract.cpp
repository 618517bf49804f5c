#include "fuzz/fuzz_contract.h"

#include <cxxabi.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>
#include <typeinfo>

namespace neurocloth::fuzz {

void finding(const char* reader, const std::string& what) {
  std::fprintf(stderr, "\nneurocloth fuzz finding (%s): %s\n", reader, what.c_str());
  std::fflush(stderr);
  std::abort();
}

std::string type_name(const std::exception& e) {
  const char* mangled = typeid(e).name();
  int status = 0;
  const std::unique_ptr<char, void (*)(void*)> name(
      abi::__cxa_demangle(mangled, nullptr, nullptr, &status), std::free);
  return status == 0 && name ? name.get() : mangled;
}

bool skip_known() {
  static const bool skip = [] {
    const char* v = std::getenv("NEUROCLOTH_FUZZ_SKIP_KNOWN");
    return v != nullptr && std::strcmp(v, "1") == 0;
  }();
  return skip;
}

std::string show(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

void Contract::finite(double v, const std::string& what) const {
  if (!std::isfinite(v)) fail(what + " accepted as " + show(v) + " (not finite)");
}

void Contract::vector(const Vec3& v, const std::string& what) const {
  for (int k = 0; k < 3; ++k)
    finite(v[k], what + "[" + std::to_string(k) + "]");
  require_known(std::isfinite(v.squaredNorm()),
                what + " accepted as [" + show(v.x()) + ", " + show(v.y()) + ", " + show(v.z()) +
                    "]: finite, but its norm overflows to infinity");
}

}  // namespace neurocloth::fuzz
