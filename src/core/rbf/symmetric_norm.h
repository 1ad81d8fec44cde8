#pragma once
// The 1-norm of a symmetric matrix stored in its lower triangle, in one pass that also checks
// the entries are finite. It replaces LAPACKE's dlansy, which reads the triangle twice on one
// thread (a NaN scan, then the norm), and the NaN scan of LAPACKE's dpotrf: at 4 000 unknowns
// each such pass reads 64 MB (docs/performance.md, "Fit speed as users meet it").

#include <Eigen/Core>

namespace hermite {

// max_j Σ_i |M(i, j)| of the symmetric k × k matrix whose lower triangle (diagonal included) is
// the block at M with leading dimension ld ≥ k; the strict upper triangle is not read.
// NaN when any entry of the lower triangle is not finite. Threaded (OpenMP).
double lowerSymmetricOneNorm(const double* M, Eigen::Index k, Eigen::Index ld);

}  // namespace hermite
