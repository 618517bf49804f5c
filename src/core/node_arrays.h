#pragma once
// K arrays of one double per node, in one allocation, each array starting at a
// different offset modulo 4 KiB. Separate power-of-two-sized vectors all start
// at the same page offset, and then a store to force[i] and a load of x[j] a few
// kilobytes apart look alike to the CPU's store-forwarding check ("4K
// aliasing"): a 128 x 128 cloth ran 15% slower than a 130 x 130 one for it.
// Addresses only; results do not depend on the padding.
#include <array>
#include <cstddef>
#include <vector>

namespace neurocloth {

// A view of one array of a NodeArrays block; behaves like a fixed-size vector.
class NodeArray {
 public:
  double* data() { return p_; }
  const double* data() const { return p_; }
  std::size_t size() const { return n_; }
  double& operator[](std::size_t i) { return p_[i]; }
  double operator[](std::size_t i) const { return p_[i]; }
  double* begin() { return p_; }
  double* end() { return p_ + n_; }
  const double* begin() const { return p_; }
  const double* end() const { return p_ + n_; }

 private:
  template <int K>
  friend class NodeArrays;
  double* p_ = nullptr;
  std::size_t n_ = 0;
};

std::size_t next_node_array_stagger();  // a different start offset per block

template <int K>
class NodeArrays {
 public:
  explicit NodeArrays(std::size_t n = 0) { resize(n); }
  NodeArrays(const NodeArrays& o)
      : storage_(o.storage_), n_(o.n_), start_(o.start_), stride_(o.stride_) {
    bind();
  }
  NodeArrays& operator=(const NodeArrays& o) {
    if (this != &o) {
      if (o.n_ == n_) {
        for (int k = 0; k < K; ++k)
          std::copy(o.arrays_[k]->begin(), o.arrays_[k]->end(), arrays_[k]->begin());
      } else {
        storage_ = o.storage_;
        n_ = o.n_;
        start_ = o.start_;
        stride_ = o.stride_;
        bind();
      }
    }
    return *this;
  }
  std::size_t size() const { return n_; }
  // Bytes held (0 for an empty block: a buffer a scene does not need costs nothing).
  std::size_t allocated_bytes() const { return storage_.capacity() * sizeof(double); }
  void resize(std::size_t n) {
    n_ = n;
    if (n == 0) {
      std::vector<double>().swap(storage_);
      start_ = stride_ = 0;
      bind();
      return;
    }
    // Each array is padded to a cache line plus 9 lines, so consecutive arrays
    // fall 576 bytes apart modulo 4 KiB; blocks start at a rotating offset.
    stride_ = (n + 7) / 8 * 8 + 72;
    start_ = 72 * (next_node_array_stagger() % 7);
    storage_.assign(start_ + K * stride_, 0.0);
    bind();
  }

 protected:
  // Derived classes list their named arrays here, in order.
  void set_arrays(std::array<NodeArray*, K> arrays) {
    arrays_ = arrays;
    bind();
  }

 private:
  void bind() {
    for (int k = 0; k < K; ++k)
      if (arrays_[k]) {
        arrays_[k]->p_ = storage_.data() + start_ + k * stride_;
        arrays_[k]->n_ = n_;
      }
  }
  std::vector<double> storage_;
  std::size_t n_ = 0, start_ = 0, stride_ = 0;
  std::array<NodeArray*, K> arrays_{};
};

}  // namespace neurocloth
