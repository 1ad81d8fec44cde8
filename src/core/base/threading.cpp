#include "core/base/threading.h"

#include <omp.h>
#include <sched.h>

#include <cstdio>
#include <algorithm>
#include <chrono>
#include <thread>

extern "C" void openblas_set_num_threads(int num_threads);
extern "C" int openblas_get_num_threads(void);

namespace hermite {

void setThreadCount(int n) {
  if (n < 1) n = 1;
  omp_set_num_threads(n);
  openblas_set_num_threads(n);
}

void setBlasThreadCount(int n) {
  // OpenBLAS built for OpenMP sets OpenMP's count with its own; the OpenMP loops keep theirs.
  const int openmp = omp_get_max_threads();
  openblas_set_num_threads(n < 1 ? 1 : n);
  omp_set_num_threads(openmp);
}

int threadCount() { return omp_get_max_threads(); }

int blasThreadCount() { return openblas_get_num_threads(); }

int availableCores() {
  // The CPUs this process may run on (taskset, cgroup cpusets), else all of the machine's.
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : static_cast<int>(n);
}

namespace {

// Runnable scheduling entities of the whole machine now (/proc/loadavg: "0.52 0.58 0.59 3/467 …"),
// or -1 when unreadable.
int runnableNow() {
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  if (f == nullptr) return -1;
  double a, b, c;
  int runnable = 0, total = 0;
  const int read = std::fscanf(f, "%lf %lf %lf %d/%d", &a, &b, &c, &runnable, &total);
  std::fclose(f);
  return read == 5 ? runnable : -1;
}

}  // namespace

int idleCores(bool confirm) {
  const int cores = availableCores();
  int others = runnableNow() - 1;  // the caller is running
  if (others >= 1 && confirm) {
    // Busy for longer than a moment: a process starting up (the shell reading this program's
    // output) is runnable for a few milliseconds and does not halve a fit; a competing one is.
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    others = std::min(others, runnableNow() - 1);
  }
  return others <= 0 ? cores : (others >= cores ? 1 : cores - others);
}

BlasThreadsForLoad::BlasThreadsForLoad(bool large)
    : previous_(openblas_get_num_threads()), previousOpenmp_(omp_get_max_threads()) {
  // Inside a parallel region (partition-of-unity boxes) other threads may be in BLAS calls while
  // this one would change the count under them: left alone there.
  threads_ = previous_ > 1 && !omp_in_parallel() ? std::min(previous_, idleCores(large)) : previous_;
  // Both counts: OpenBLAS built for OpenMP takes its threads from OpenMP's count at each call.
  if (threads_ != previous_) {
    openblas_set_num_threads(threads_);
    omp_set_num_threads(std::min(threads_, previousOpenmp_));
  }
}

BlasThreadsForLoad::~BlasThreadsForLoad() {
  if (threads_ != previous_) {
    openblas_set_num_threads(previous_);
    omp_set_num_threads(previousOpenmp_);
  }
}

}  // namespace hermite
