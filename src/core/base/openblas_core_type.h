#pragma once
/* The best OpenBLAS core type this CPU's feature flags allow ("SKYLAKEX", "HASWELL",
 * "SANDYBRIDGE"), or a null pointer. C and C++: the launcher (src/launcher/launcher.c) depends on
 * libc alone and shares this with core/base/blas_setup.cpp. */

static inline const char* openblasCoreTypeFromFlags(void) {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512cd"))
    return "SKYLAKEX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "HASWELL";
  if (__builtin_cpu_supports("avx")) return "SANDYBRIDGE";
  return 0;
}
