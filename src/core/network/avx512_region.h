#pragma once
// Code compiled for AVX-512 F and VL inside a build that targets plain x86-64
// (cpu_features.h): every function *defined* between NEUROCLOTH_AVX512_BEGIN
// and NEUROCLOTH_AVX512_END is compiled for that target, lambdas and templates
// included; everything outside stays baseline. Such code runs only after
// cpu_has_avx512() said yes.
//
// The rule that keeps a baseline CPU from ever executing it: inside a region,
// define only what has internal linkage or what no baseline file defines too.
// An inline function or a template instantiation defined in a region and
// also elsewhere would be one symbol to the linker, which may keep the
// AVX-512 copy for every caller. So a region file includes every header it
// needs before BEGIN (their inline functions stay baseline; the compiler may
// still inline them into region code), and inside only headers written for a
// region (spring_chunk_avx512.h) or templates instantiated there on the
// region's own types (spring_sweep.h). Region files are compiled on their own,
// never batched with other sources (CMAKE_UNITY_BUILD would include headers
// before the region and merge anonymous namespaces).
#if defined(__x86_64__) || defined(_M_X64)
#define NEUROCLOTH_AVX512_REGION 1
// _Pragma takes one string literal: clang-format must not split it in two.
// clang-format off
#if defined(__clang__)
#define NEUROCLOTH_AVX512_BEGIN _Pragma("clang attribute push(__attribute__((target(\"avx512f,avx512vl\"))), apply_to = function)")
#define NEUROCLOTH_AVX512_END _Pragma("clang attribute pop")
#elif defined(__GNUC__)
#define NEUROCLOTH_AVX512_BEGIN \
  _Pragma("GCC push_options") _Pragma("GCC target(\"avx512f,avx512vl\")")
#define NEUROCLOTH_AVX512_END _Pragma("GCC pop_options")
// clang-format on
#else
#error "an AVX-512 region needs GCC or clang"
#endif
#endif
