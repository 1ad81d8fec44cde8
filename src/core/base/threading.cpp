#include "core/base/threading.h"

#include <omp.h>

#include <thread>

extern "C" void openblas_set_num_threads(int num_threads);

namespace hermite {

void setThreadCount(int n) {
  if (n < 1) n = 1;
  omp_set_num_threads(n);
  openblas_set_num_threads(n);
}

void setBlasThreadCount(int n) { openblas_set_num_threads(n < 1 ? 1 : n); }

int threadCount() { return omp_get_max_threads(); }

int availableCores() {
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

}  // namespace hermite
