#pragma once
// One place that sets how many worker threads the program uses: OpenMP loops (batch
// evaluation, assembly) and OpenBLAS (dense factorisations). `--threads N` calls it.

namespace hermite {

// n ≥ 1. Affects both OpenMP and OpenBLAS.
void setThreadCount(int n);
// OpenBLAS alone (n ≥ 1), OpenMP's count kept: many small factorisations run side by side (one
// per hole in hole filling, one per partition-of-unity box) go faster with one BLAS thread each;
// setThreadCount restores both. (OpenBLAS built for OpenMP runs single-threaded inside a parallel
// region by itself and takes OpenMP's count elsewhere.)
void setBlasThreadCount(int n);
// The current OpenMP worker count.
int threadCount();
// The current OpenBLAS thread count.
int blasThreadCount();
// Hardware threads available to this process: its CPU affinity mask (sched_getaffinity), else
// std::thread::hardware_concurrency.
int availableCores();

// Cores not busy with other work: availableCores() minus the machine's runnable tasks other than
// the caller (/proc/loadavg's instantaneous count; with `confirm`, the smaller of two readings
// 5 ms apart when the first finds any), at least 1.
int idleCores(bool confirm = true);

// For one BLAS call sequence: OpenBLAS and the OpenMP loops of the calling thread get no more
// threads than idleCores() (a thread sharing a core with another busy process makes every
// synchronisation of a factorisation wait for it: 4–10× slower fits, docs/performance.md); the
// previous counts come back at the end. Work that is not `large` takes one reading without the
// 5 ms confirmation: a process that was runnable only for a moment costs such work a few
// milliseconds at most, while a thread sharing a core with a busy one costs a small fit several
// times its time (docs/performance.md).
// Inside an OpenMP parallel region it changes nothing.
class BlasThreadsForLoad {
 public:
  explicit BlasThreadsForLoad(bool large);
  ~BlasThreadsForLoad();
  BlasThreadsForLoad(const BlasThreadsForLoad&) = delete;
  BlasThreadsForLoad& operator=(const BlasThreadsForLoad&) = delete;
  int threads() const { return threads_; }

 private:
  int previous_ = 0;
  int previousOpenmp_ = 0;
  int threads_ = 0;
};

}  // namespace hermite
