#pragma once
// The contract every reader's harness checks (docs/robustness.md, "Fuzzing"):
// a reader given any bytes either throws neurocloth::InputError or returns an
// object in which every number is finite. Anything else -- another exception,
// a crash, a non-finite value accepted -- is a finding: the harness prints what
// it saw and aborts, so libFuzzer keeps the input.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>

#include "core/base/vec3.h"
#include "core/io/input_error.h"

namespace neurocloth::fuzz {

// Prints "neurocloth fuzz finding (READER): WHAT" and aborts.
[[noreturn]] void finding(const char* reader, const std::string& what);

// The dynamic type of an exception, demangled ("std::bad_alloc").
std::string type_name(const std::exception& e);

// A double with every digit that tells it apart ("4.9406564584124654e-324").
std::string show(double v);

// True when NEUROCLOTH_FUZZ_SKIP_KNOWN=1: violations of a kind the lead is
// already fixing (docs/robustness.md lists them) are let through, so a long
// campaign looks for new kinds instead of rediscovering those.
bool skip_known();

// The known quadratic time of tinyobjloader on one long line (a face of
// 60,000 indices): a campaign that skips known kinds leaves lines over 4 KiB
// alone (obj_fuzzer.cpp, obstacle_fuzzer.cpp).
inline bool long_line(const std::uint8_t* data, std::size_t size) {
  std::size_t run = 0;
  for (std::size_t i = 0; i < size; ++i) {
    run = data[i] == '\n' ? 0 : run + 1;
    if (run > 4096) return true;
  }
  return false;
}

// Runs `read` under the exception contract: the object it returns, or nothing
// when it refused the input with InputError.
template <class Read>
auto accepted(const char* reader, Read&& read) -> std::optional<decltype(read())> {
  try {
    return read();
  } catch (const InputError&) {
    return std::nullopt;
  } catch (const std::exception& e) {
    finding(reader, "escaped " + type_name(e) + " (only InputError may): " + e.what());
  } catch (...) {
    finding(reader, "escaped an exception that is not a std::exception");
  }
}

// Every component finite and the squared norm too (see Contract::vector): the
// cheap test hot loops make before wording a message.
inline bool finite_norm(const Vec3& v) {
  return std::isfinite(v.squaredNorm());
}

// The checks on an accepted object; `what` names the value ("gravity").
class Contract {
 public:
  explicit Contract(const char* reader) : reader_(reader) {}

  [[noreturn]] void fail(const std::string& what) const { finding(reader_, what); }
  void require(bool ok, const std::string& what) const {
    if (!ok) fail(what);
  }
  // A violation of a kind already known (skip_known() lets it through).
  void require_known(bool ok, const std::string& what) const {
    if (!ok && !skip_known()) fail(what + " [known kind]");
  }
  void finite(double v, const std::string& what) const;
  // Finite, and so is its squared norm: the core measures every vector with
  // Eigen's norm() (the square root of squaredNorm()), and a component above
  // ~1e154 makes that infinite although the number itself is finite.
  void vector(const Vec3& v, const std::string& what) const;

 private:
  const char* reader_;
};

}  // namespace neurocloth::fuzz
