# Known compiler false positives, in one place: which, why, and for which
# builds. Warnings are errors for our code (NEUROCLOTH_WERROR); a warning that
# a compiler raises inside its own headers or Eigen's, for one target CPU
# only, would otherwise fail a build on one machine and pass it on another.
include(CheckCXXSourceCompiles)

# Whether the target flags let the compiler use AVX-512 everywhere (not only
# in our AVX-512 regions): -march=native on such a CPU, skylake-avx512, znver4,
# or znver3 with -mavx512f.
set(CMAKE_REQUIRED_FLAGS "${neurocloth_target_flags}")
string(REPLACE ";" " " CMAKE_REQUIRED_FLAGS "${CMAKE_REQUIRED_FLAGS}")
check_cxx_source_compiles("
#if !defined(__AVX512F__)
#error no AVX-512
#endif
int main() { return 0; }" NEUROCLOTH_TARGET_HAS_AVX512)
unset(CMAKE_REQUIRED_FLAGS)

# GCC 12, targeting AVX-512: avx512fintrin.h builds its 512-bit packets'
# "undefined" halves from self-initialised variables (GCC bug 105593, fixed in
# GCC 13), so wherever Eigen transposes, reduces or extracts AVX-512 packets
# (dense eigensolvers, matrix products, norm(), dot()) GCC reports
# "'__Y' is used uninitialized" (-Wuninitialized, at -O2 and at -O1) and
# "may be used uninitialized" (-Wmaybe-uninitialized) inside those headers,
# inlined into whichever of our functions called Eigen. Both are off for such
# builds only: the default x86-64 build, which CI builds and tests, keeps them
# on (and as errors) for all of our code, and it compiles the same sources.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13
   AND NEUROCLOTH_TARGET_HAS_AVX512)
  message(STATUS "neurocloth: GCC ${CMAKE_CXX_COMPILER_VERSION} targeting AVX-512 "
                 "(${neurocloth_target_flags}): -Wuninitialized and -Wmaybe-uninitialized off "
                 "(GCC bug 105593 in avx512fintrin.h; cmake/compiler_workarounds.cmake)")
  target_compile_options(neurocloth_flags INTERFACE -Wno-uninitialized -Wno-maybe-uninitialized)
endif()
