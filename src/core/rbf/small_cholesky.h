#pragma once
// In-place Cholesky factorisation A = L Lᵀ of the small symmetric positive definite systems of the
// partition of unity's local fits (30–800 unknowns, usually 40–120; pu_local_fit.h), with the
// 1-norm reciprocal condition estimate and the solve of Eigen's LLT.
//
// Eigen's LLT factorises blocks of 8 columns from 32 unknowns on (a rank-8 update of the
// trailing matrix per block, repacked every time); here the factorisation is Eigen's unblocked
// column loop up to kSmallCholeskyUnblockedUpTo unknowns and Eigen's blocked loop with 32-column
// blocks above — about a quarter less time at 44–120 unknowns (build/release/local_cholesky_bench,
// docs/performance.md). The factor equals Eigen's up to rounding (the same operations, summed in
// other groupings).

#include <Eigen/Core>

namespace hermite {

// Systems up to this size are factorised column by column.
inline constexpr Eigen::Index kSmallCholeskyUnblockedUpTo = 40;

class SmallCholesky {
 public:
  // Factorises the lower triangle of A in place (the strict upper triangle is neither read nor
  // written); A must outlive this object.
  explicit SmallCholesky(Eigen::Ref<Eigen::MatrixXd> A);

  // Whether A was positive definite (every pivot > 0).
  bool ok() const { return ok_; }
  // 1 / (‖A‖₁ · est ‖A⁻¹‖₁), as Eigen's LLT::rcond() (cholesky_condition.h); ok() only.
  double rcond() const;
  // A⁻¹b by the two triangular solves Eigen's LLT::solve makes; ok() only.
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  Eigen::Ref<Eigen::MatrixXd> L_;
  double norm_ = 0;  // ‖A‖₁ before the factorisation (NaN or ∞ when an entry is not finite)
  bool ok_ = false;
};

}  // namespace hermite
