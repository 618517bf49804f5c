#pragma once
// An owning pointer that copies what it points to (through T::clone()), so a
// class holding polymorphic parts — an integrator, a module's state — stays
// copyable by value with defaulted copy and move.
#include <memory>
#include <utility>

namespace neurocloth {

template <class T>
class Cloned {
 public:
  Cloned() = default;
  Cloned(std::unique_ptr<T> p) : p_(std::move(p)) {}  // NOLINT: implicit, like unique_ptr's
  Cloned(const Cloned& o) : p_(o.p_ ? o.p_->clone() : nullptr) {}
  Cloned& operator=(const Cloned& o) {
    if (this != &o) p_ = o.p_ ? o.p_->clone() : nullptr;
    return *this;
  }
  Cloned(Cloned&&) noexcept = default;
  Cloned& operator=(Cloned&&) noexcept = default;

  T* get() const { return p_.get(); }
  T* operator->() const { return p_.get(); }
  T& operator*() const { return *p_; }
  explicit operator bool() const { return p_ != nullptr; }

 private:
  std::unique_ptr<T> p_;
};

}  // namespace neurocloth
