#include "core/base/threading.h"

#include <omp.h>
#include <sched.h>

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
  // The CPUs this process may run on (taskset, cgroup cpusets), else all of the machine's.
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

}  // namespace hermite
