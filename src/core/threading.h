#pragma once
// One place that sets how many worker threads the program uses: OpenMP loops (batch
// evaluation, assembly) and OpenBLAS (dense factorisations). `--threads N` calls it.

namespace hermite {

// n ≥ 1. Affects both OpenMP and OpenBLAS.
void setThreadCount(int n);
// The current OpenMP worker count.
int threadCount();
// Hardware threads available to this process.
int availableCores();

}  // namespace hermite
