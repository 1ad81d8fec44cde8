#pragma once
// The 1-norm condition estimate of a small symmetric positive definite matrix A = L Lᵀ from its
// lower Cholesky factor, as the partition of unity's local fits need it 70 000 times per fit
// (pu_local_fit.h; docs/maths.md, Solvers and conditioning).
//
// The estimate of ‖A⁻¹‖₁ takes the steps of Eigen's rcond_invmatrix_L1_norm_estimate, the
// Hager–Higham estimator LAPACK's dlacn2 also implements (Higham, "FORTRAN codes for estimating
// the one-norm of a real or complex matrix", ACM TOMS 14, 1988): A⁻¹(e/n), then at most four
// ascent steps A⁻¹ sign(v) → j = argmax → A⁻¹eⱼ, and the alternating test vector
// xᵢ = (−1)ⁱ(1 + i/(n−1)), giving max(‖A⁻¹eⱼ‖₁, 2‖A⁻¹x‖₁/(3n)). It pays less than Eigen's:
//  - A⁻¹(e/n) and A⁻¹x share one pass over L in each direction (two right-hand sides);
//  - A⁻¹eⱼ starts the forward substitution at row j (rows above it stay zero);
//  - the vectors live in per-thread buffers (no heap allocation per call).
// The result equals Eigen's LLT::rcond() up to rounding in the triangular solves.

#include <Eigen/Core>

namespace hermite {

// Estimate of ‖(L Lᵀ)⁻¹‖₁ (a lower bound on it, and within a small factor of LAPACK's dpocon
// estimate), for the n × n lower triangular L (diagonal included, positive) stored column-major
// at L with leading dimension ld ≥ n; the strict upper triangle is not read. 0 for n = 0.
double choleskyInverseNormEstimate(const double* L, Eigen::Index n, Eigen::Index ld);

// The reciprocal condition number estimate 1 / (‖A‖₁ · est ‖A⁻¹‖₁) from A's 1-norm and its
// factor, with Eigen's conventions: ∞ for n = 0, 0 for a zero norm or a zero inverse estimate,
// 1 for n = 1.
double choleskyReciprocalCondition(double aNorm, const double* L, Eigen::Index n, Eigen::Index ld);

}  // namespace hermite
