#include "core/blas_setup.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>

extern "C" char* openblas_get_corename(void);

namespace hermite {

namespace {

// The best OpenBLAS core type this CPU's feature flags allow, or nullptr.
const char* coreTypeFromFlags() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
      __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512bw") &&
      __builtin_cpu_supports("avx512cd"))
    return "SKYLAKEX";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "HASWELL";
  if (__builtin_cpu_supports("avx")) return "SANDYBRIDGE";
  return nullptr;
}

bool isGenericCore(const char* name) {
  for (const char* generic : {"Prescott", "Core2", "Katmai", "Coppermine", "Northwood", "Banias", "Atom",
                              "Nehalem", "Penryn", "Dunnington", "Unknown"})
    if (std::strcmp(name, generic) == 0) return true;
  return false;
}

}  // namespace

const char* blasCoreName() { return openblas_get_corename(); }

void reexecWithTunedBlas(char** argv) {
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr) return;  // the user's choice, or already re-executed
  const char* current = openblas_get_corename();
  if (current == nullptr || !isGenericCore(current)) return;
  const char* better = coreTypeFromFlags();
  if (better == nullptr) return;
  if (setenv("OPENBLAS_CORETYPE", better, 1) != 0) return;
  execv("/proc/self/exe", argv);
  // execv failed: go on with the generic kernels (correct, only slower).
}

}  // namespace hermite
