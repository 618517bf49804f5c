// Fuzzes the window's script reader, load_script() (src/app/viewer/viewer_script.cpp,
// compiled into this harness alone). It takes a path, so the bytes go through
// this process's own file. An accepted script must hold finite times, in
// order, finite coordinates and amounts, and no key written twice.
#include <cmath>
#include <cstdint>
#include <string>

#include "app/viewer/viewer_script.h"
#include "fuzz/fuzz_contract.h"
#include "fuzz/fuzz_input_file.h"
#include "fuzz/json_duplicate_keys.h"

namespace neurocloth::fuzz {
namespace {

void check_script(const Contract& c, const Script& s, const std::string& text) {
  for (std::size_t i = 0; i < s.events.size(); ++i) {
    const ScriptEvent& e = s.events[i];
    const std::string f = "events[" + std::to_string(i) + "]";
    c.finite(e.t, f + ".t");
    c.require(e.t >= 0, f + ".t accepted < 0");
    if (i > 0) c.require(e.t >= s.events[i - 1].t, f + ".t accepted out of time order");
    c.finite(e.x, f + ".x");
    c.finite(e.y, f + ".y");
    c.finite(e.duration, f + ".duration");
    c.require(e.duration >= 0, f + ".duration accepted < 0");
    c.finite(e.amount, f + " amount (steps or value)");
    c.require(e.node >= -1, f + ".node accepted < 0");
  }
  const std::string duplicate = first_duplicate_key(text);
  c.require_known(duplicate.empty(), "accepted a document that names key '" + duplicate +
                                         "' twice in one object (the last silently wins)");
}

}  // namespace
}  // namespace neurocloth::fuzz

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace neurocloth;
  static fuzz::InputFile file("script.json");
  const std::string& path = file.write(data, size);
  const auto script = fuzz::accepted("script", [&] { return load_script(path); });
  file.remove();
  if (script)
    fuzz::check_script(fuzz::Contract("script"), *script,
                       std::string(reinterpret_cast<const char*>(data), size));
  return 0;
}
