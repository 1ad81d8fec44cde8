#pragma once
// The machine's yardstick for the fit benches: plain LAPACK (OpenBLAS) factorisations of a given
// size, so that a fit's factorisation speed can be read against what the library reaches alone.

#include <Eigen/Core>

#include "core/rbf/dense_solver.h"

namespace hermite {

// GFLOP/s (10⁹ floating-point operations per second, factorisationFlops) of a plain dpotrf
// (Cholesky paths) or dgetrf (LU and LDLᵀ paths) of a well-conditioned k × k matrix: the median of
// `repeats` runs on a fresh copy each time.
double plainLapackGflops(SolverChoice path, Eigen::Index k, int repeats);

// The size k of the block a path factorised, from its flop count (the inverse of factorisationFlops).
Eigen::Index factorisedSize(SolverChoice path, double flops);

}  // namespace hermite
