#include "core/base/blas_setup.h"

#include "core/base/openblas_core_type.h"

#include <unistd.h>

#include <cstdlib>
#include <cstring>

extern "C" char* openblas_get_corename(void);

namespace hermite {

namespace {

bool isGenericCore(const char* name) {
  for (const char* generic : {"Prescott", "Core2", "Katmai", "Coppermine", "Northwood", "Banias", "Atom",
                              "Nehalem", "Penryn", "Dunnington", "Unknown"})
    if (std::strcmp(name, generic) == 0) return true;
  return false;
}

}  // namespace

const char* blasCoreName() { return openblas_get_corename(); }

void reexecWithTunedBlas(char** argv) {
  if (std::getenv("HERMITE_REEXECUTED") != nullptr) return;  // once only
  bool reexec = false;
  // libgomp threads spin after each parallel region by default and then fight OpenBLAS's
  // threads for the cores, which roughly doubles a small fit (docs/performance.md). libgomp
  // reads this at load time.
  if (std::getenv("OMP_WAIT_POLICY") == nullptr) {
    setenv("OMP_WAIT_POLICY", "PASSIVE", 1);
    reexec = true;
  }
  // OpenBLAS's worker threads spin in sched_yield for 2^28 cycles (~0.1 s) after each threaded
  // call before they sleep, taking a core from the renderer's threads on a small machine while
  // the GUI drags a sample; 2^16 cycles (~25 µs) still bridge the calls inside one factorisation.
  if (std::getenv("OPENBLAS_THREAD_TIMEOUT") == nullptr) {
    setenv("OPENBLAS_THREAD_TIMEOUT", "16", 1);
    reexec = true;
  }
  const char* current = openblas_get_corename();
  if (std::getenv("OPENBLAS_CORETYPE") == nullptr && current != nullptr && isGenericCore(current)) {
    if (const char* better = openblasCoreTypeFromFlags()) {
      setenv("OPENBLAS_CORETYPE", better, 1);
      reexec = true;
    }
  }
  if (!reexec) return;
  setenv("HERMITE_REEXECUTED", "1", 1);
  execv("/proc/self/exe", argv);
  // execv failed: go on as we are (correct, only slower).
}

}  // namespace hermite
