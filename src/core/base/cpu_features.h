#pragma once
// What the CPU running this process can do, asked at run time. Every build
// targets a declared instruction set (CMakeLists.txt, NEUROCLOTH_TARGET_FLAGS:
// x86-64 baseline by default), never the building machine's, so one binary
// runs on any x86-64; code for newer instructions is compiled for its own
// target (avx512_region.h) and chosen here, per process (spring_kernel.h).
#include <string>

namespace neurocloth {

// The environment variable that makes a process behave as if its CPU lacked
// features: a comma- or space-separated list of names (kMaskableCpuFeatures).
// How a user or a test reproduces, on an AVX-512 machine, what a CPU without
// it runs (the portable kernel, its determinism hashes).
inline constexpr const char* kDisableCpuFeaturesVariable = "NEUROCLOTH_DISABLE_CPU_FEATURES";
inline constexpr const char* kMaskableCpuFeatures = "avx512";

// AVX-512 F and VL: on an x86-64 CPU that reports both, whose operating system
// saves the mask and 512-bit registers (the compiler's run-time check reads
// XCR0 for that), and not masked by kDisableCpuFeaturesVariable. Always false
// on other architectures. Read once per process.
bool cpu_has_avx512();

// Whether the CPU reports AVX-512 F and VL, whatever the variable says.
bool cpu_reports_avx512();

// Why the variable's value cannot be read ("" when it is unset or fine): a name
// it does not know. Programs check it at start and refuse to run with it, so a
// misspelt mask never silently leaves the fast kernel on (cli_main, viewer).
std::string disabled_cpu_features_error();

}  // namespace neurocloth
