#pragma once
// One array of doubles per node, allocated so that the arrays of a state do not
// start at the same offset modulo 4 KiB. Large vectors of a power-of-two size
// all come back page-aligned, and then a store to force[i] and a load of x[j] a
// few kilobytes apart look alike to the CPU's store-forwarding check ("4K
// aliasing"): a 128 x 128 cloth ran 15% slower than a 130 x 130 one for it.
// The arrays are plain vectors, so a state is copied and moved by value: no
// view points into its owner. Addresses only; results do not depend on them.
#include <cstddef>
#include <cstring>
#include <new>
#include <vector>

namespace neurocloth {

std::size_t next_node_array_stagger();  // a different start offset per allocation

// Shifts each allocation by one cache line plus 0..6 times 576 bytes (nine
// lines): consecutive arrays then start 576 bytes apart modulo 4 KiB.
template <class T>
struct StaggeredAllocator {
  using value_type = T;
  StaggeredAllocator() = default;
  template <class U>
  StaggeredAllocator(const StaggeredAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t shift = kLine + kStagger * (next_node_array_stagger() % 7);
    char* raw = static_cast<char*>(::operator new(n * sizeof(T) + shift, std::align_val_t(kLine)));
    char* p = raw + shift;
    std::memcpy(p - sizeof shift, &shift, sizeof shift);  // read back by deallocate
    return reinterpret_cast<T*>(p);
  }
  void deallocate(T* p, std::size_t) noexcept {
    char* c = reinterpret_cast<char*>(p);
    std::size_t shift;
    std::memcpy(&shift, c - sizeof shift, sizeof shift);
    ::operator delete(c - shift, std::align_val_t(kLine));
  }
  friend bool operator==(const StaggeredAllocator&, const StaggeredAllocator&) { return true; }
  friend bool operator!=(const StaggeredAllocator&, const StaggeredAllocator&) { return false; }

 private:
  static constexpr std::size_t kLine = 64, kStagger = 576;
};

using NodeArray = std::vector<double, StaggeredAllocator<double>>;

inline std::size_t allocated_bytes(const NodeArray& a) {
  return a.capacity() * sizeof(double);
}

}  // namespace neurocloth
