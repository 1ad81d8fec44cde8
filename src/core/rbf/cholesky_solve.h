#pragma once
// Solves with a lower Cholesky factor for one right-hand side, in column panels: a small
// triangular solve (dtrsv) per diagonal block and a matrix-vector product (dgemv) for the rows
// below it. OpenBLAS runs dgemv on all its threads but dtrsv on one, so on large factors this is
// about twice as fast as LAPACK's dpotrs, which is one dtrsv per triangle (docs/performance.md).
// The condition estimate makes five such solves after each Cholesky factorisation.

#include <Eigen/Core>

namespace hermite {

// v ← (L Lᵀ)⁻¹ v, with L the lower triangle (diagonal included) of the k × k block at L with
// leading dimension ld; v has k entries. The strict upper triangle of the block is not read.
void solveWithCholeskyFactor(const double* L, Eigen::Index k, Eigen::Index ld, Eigen::Ref<Eigen::VectorXd> v);

}  // namespace hermite
