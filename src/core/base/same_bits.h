#pragma once
// Bit-for-bit equality, the test a saved and a restored run must pass (a NaN
// equals itself, 0.0 differs from -0.0): the same bits, not close values.
#include <cstring>
#include <vector>

namespace neurocloth {

inline bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

// Arrays of plain values (double, int32, ...), compared by their bytes.
template <class T, class A>
bool same_bits(const std::vector<T, A>& a, const std::vector<T, A>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

}  // namespace neurocloth
