#pragma once
// The functions between ENGINE_AVX2_BEGIN and ENGINE_AVX2_END are compiled for AVX2,
// whatever the build's target; callers run them only where cpuHasAvx2() says the CPU
// has it. GCC's target pragma, or clang's equivalent (the sanitizer tree builds with
// clang).
// ENGINE_AVX512_BEGIN/END likewise for AVX2 code that may also use AVX-512VL's 32
// registers and mask instructions (callers check cpuHasAvx512()).
#if defined(__clang__)
#define ENGINE_AVX2_BEGIN _Pragma("clang attribute push(__attribute__((target(\"avx2\"))), apply_to = function)")
#define ENGINE_AVX2_END _Pragma("clang attribute pop")
#define ENGINE_AVX512_BEGIN \
  _Pragma("clang attribute push(__attribute__((target(\"avx2,avx512f,avx512vl\"))), apply_to = function)")
#define ENGINE_AVX512_END _Pragma("clang attribute pop")
#else
#define ENGINE_AVX2_BEGIN _Pragma("GCC push_options") _Pragma("GCC target(\"avx2\")")
#define ENGINE_AVX2_END _Pragma("GCC pop_options")
#define ENGINE_AVX512_BEGIN _Pragma("GCC push_options") _Pragma("GCC target(\"avx2,avx512f,avx512vl\")")
#define ENGINE_AVX512_END _Pragma("GCC pop_options")
#endif

namespace engine::rt {
// Whether the CPU runs AVX2, asked of it once.
inline bool cpuHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
// Whether it also runs AVX-512F and VL (what ENGINE_AVX512_BEGIN's code may use).
inline bool cpuHasAvx512() {
  static const bool has = cpuHasAvx2() && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
  return has;
}
}  // namespace engine::rt
