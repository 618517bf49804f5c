#pragma once
// Wall time a module has spent, for RESULT.json and the viewer. A diagnostic
// the simulation keeps beside its state; no step reads it.
#include <chrono>

namespace neurocloth {

struct ModuleClock {
  double seconds = 0;
  long calls = 0;
};

// Times one call into `clock` (two steady_clock reads: tens of ns per call).
class ScopedModuleTimer {
 public:
  explicit ScopedModuleTimer(ModuleClock& c)
      : clock_(c), start_(std::chrono::steady_clock::now()) {}
  ~ScopedModuleTimer() {
    clock_.seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    ++clock_.calls;
  }
  ScopedModuleTimer(const ScopedModuleTimer&) = delete;
  ScopedModuleTimer& operator=(const ScopedModuleTimer&) = delete;

 private:
  ModuleClock& clock_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace neurocloth
