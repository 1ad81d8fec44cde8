#include <malloc.h>

#include "app/commands/cli.h"
#include "core/base/blas_setup.h"

int main(int argc, char** argv) {
  hermite::reexecWithTunedBlas(argv);
  // Keep large freed blocks in the heap instead of returning them to the kernel: the GUI and the
  // fits allocate the same multi-megabyte buffers again and again (tessellations, grids, kernel
  // matrices), and with glibc's defaults each one is a fresh mmap whose first touch page-faults
  // (docs/performance.md).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  return hermite::app::runCli(argc, argv);
}
