#include "core/network/cloth_state.h"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace neurocloth {

std::size_t next_node_array_stagger() {
  static std::atomic<std::size_t> counter{0};
  return counter++;
}

bool ClothState::all_finite() const {
  // A double is NaN or Inf exactly when its exponent bits are all ones. Testing
  // the bits with integer ops (OR-reduced) vectorises; std::isfinite in a loop
  // with an early exit does not, and this runs at the end of every advance().
  constexpr std::uint64_t kExponent = 0x7FF0000000000000ull;
  std::uint64_t bad = 0;
  for (const NodeArray* a : {&x, &y, &z, &vx, &vy, &vz}) {
    const double* p = a->data();
    for (std::size_t i = 0; i < a->size(); ++i) {
      std::uint64_t bits;
      std::memcpy(&bits, p + i, sizeof bits);
      bad |= static_cast<std::uint64_t>((bits & kExponent) == kExponent);
    }
  }
  return bad == 0;
}

}  // namespace neurocloth
