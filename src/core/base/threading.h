#pragma once
// One place that sets how many worker threads the program uses: OpenMP loops (batch
// evaluation, assembly) and OpenBLAS (dense factorisations). `--threads N` calls it.

namespace hermite {

// n ≥ 1. Affects both OpenMP and OpenBLAS.
void setThreadCount(int n);
// OpenBLAS alone (n ≥ 1): many small factorisations run side by side (one per hole in hole
// filling) go faster with one BLAS thread each; setThreadCount restores both.
void setBlasThreadCount(int n);
// The current OpenMP worker count.
int threadCount();
// Hardware threads available to this process: its CPU affinity mask (sched_getaffinity), else
// std::thread::hardware_concurrency.
int availableCores();

}  // namespace hermite
