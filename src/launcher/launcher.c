/* hermite-lab: sets the environment that libgomp and OpenBLAS read while they load, then runs
 * the program itself in its place: hermite-lab-cli (next to this file) for the commands that draw
 * nothing, hermite-lab-main for everything else.
 *
 * The program used to set these variables in main() and re-execute itself, loading its thirty
 * shared libraries twice: about one process start-up per command (docs/performance.md, Fit speed
 * as users meet it). This launcher depends on libc alone, so the second start costs little.
 * Values the user set are kept:
 *  - OMP_WAIT_POLICY=PASSIVE: spinning OpenMP workers starve OpenBLAS's threads on small machines;
 *  - OPENBLAS_THREAD_TIMEOUT=16: OpenBLAS's workers spin about 2^16 cycles after a call, not 2^28;
 *  - OPENBLAS_CORETYPE on Intel CPUs, from their feature flags: under hypervisors that hide the
 *    model, OpenBLAS otherwise falls back to its generic kernels (core/base/blas_setup.h).
 * HERMITE_REEXECUTED=1 tells the program that nothing is left to do. */

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "core/base/openblas_core_type.h"

static const char* intelCoreType(void) {
  __builtin_cpu_init();
  return __builtin_cpu_is("intel") ? openblasCoreTypeFromFlags() : 0;
}

/* The commands that draw nothing: hermite-lab-cli runs them without loading the display's
 * libraries (GLFW, EGL, X11: a dozen fewer shared libraries to map and relocate per process). */
static int headlessCommand(const char* first) {
  static const char* const names[] = {"fit", "eval", "mesh", "holefill", "patch-table"};
  for (size_t i = 0; first && i < sizeof names / sizeof names[0]; ++i)
    if (strcmp(first, names[i]) == 0) return 1;
  return 0;
}

/* The path of `program` next to this executable. */
static int programPath(const char* program, char* out, size_t size) {
  char self[PATH_MAX];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n <= 0) return 0;
  self[n] = '\0';
  char* slash = strrchr(self, '/');
  if (slash == 0) return 0;
  *slash = '\0';
  return snprintf(out, size, "%s/%s", self, program) < (int)size;
}

int main(int argc, char** argv) {
  setenv("OMP_WAIT_POLICY", "PASSIVE", 0);
  setenv("OPENBLAS_THREAD_TIMEOUT", "16", 0);
  const char* core = intelCoreType();
  if (core) setenv("OPENBLAS_CORETYPE", core, 0);
  setenv("HERMITE_REEXECUTED", "1", 1);
  char program[PATH_MAX];
  if (!programPath("hermite-lab-main", program, sizeof program)) {
    fprintf(stderr, "hermite-lab: cannot find this executable's folder (/proc/self/exe)\n");
    return 4;
  }
  char headless[PATH_MAX];
  if (argc > 1 && headlessCommand(argv[1]) && programPath("hermite-lab-cli", headless, sizeof headless))
    execv(headless, argv); /* returns only on failure: the full program runs these commands too */
  execv(program, argv);
  fprintf(stderr, "hermite-lab: cannot run %s: %s\n", program, strerror(errno));
  return 4;
}
