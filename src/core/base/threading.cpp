#include "core/base/threading.h"

#include <omp.h>
#include <sched.h>

#include <cstdio>
#include <algorithm>
#include <thread>

extern "C" void openblas_set_num_threads(int num_threads);
extern "C" int openblas_get_num_threads(void);

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

int idleCores() {
  const int cores = availableCores();
  // "0.52 0.58 0.59 3/467 12345": the fourth field is runnable/total scheduling entities now.
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if (f == nullptr) return cores;
  double a, b, c;
  int runnable = 0, total = 0;
  const int read = std::fscanf(f, "%lf %lf %lf %d/%d", &a, &b, &c, &runnable, &total);
  std::fclose(f);
  if (read != 5) return cores;
  const int others = runnable - 1;  // the caller is running
  return others <= 0 ? cores : (others >= cores ? 1 : cores - others);
}

BlasThreadsForLoad::BlasThreadsForLoad() : previous_(openblas_get_num_threads()) {
  // Inside a parallel region (partition-of-unity boxes) other threads may be in BLAS calls while
  // this one would change the count under them: left alone there.
  threads_ = previous_ > 1 && !omp_in_parallel() ? std::min(previous_, idleCores()) : previous_;
  if (threads_ != previous_) openblas_set_num_threads(threads_);
}

BlasThreadsForLoad::~BlasThreadsForLoad() {
  if (threads_ != previous_) openblas_set_num_threads(previous_);
}

}  // namespace hermite
