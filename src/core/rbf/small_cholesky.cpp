#include "core/rbf/small_cholesky.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

#include "core/rbf/cholesky_condition.h"

namespace hermite {

namespace {

using Index = Eigen::Index;
using Lower = Eigen::internal::llt_inplace<double, Eigen::Lower>;

// Columns per block of the blocked factorisation: a rank-32 update keeps the packed panels of
// Eigen's matrix product busy where rank 8 spends most of its time packing.
constexpr Index kBlockColumns = 32;

// Eigen's blocked right-looking loop (LLT.h, llt_inplace::blocked) with kBlockColumns columns per
// block. Returns the failing pivot's index, or −1.
Index blockedCholesky(Eigen::Ref<Eigen::MatrixXd>& m) {
  const Index size = m.rows();
  for (Index k = 0; k < size; k += kBlockColumns) {
    const Index bs = std::min(kBlockColumns, size - k), rs = size - k - bs;
    Eigen::Block<Eigen::Ref<Eigen::MatrixXd>> A11(m, k, k, bs, bs), A21(m, k + bs, k, rs, bs),
        A22(m, k + bs, k + bs, rs, rs);
    const Index failed = Lower::unblocked(A11);
    if (failed >= 0) return k + failed;
    if (rs == 0) continue;
    A11.adjoint().triangularView<Eigen::Upper>().solveInPlace<Eigen::OnTheRight>(A21);
    A22.selfadjointView<Eigen::Lower>().rankUpdate(A21, -1.0);
  }
  return -1;
}

// ‖A‖₁ of the symmetric A from its lower triangle, in one pass down its columns (Eigen's
// LLT::compute also reads each row's left part, with a stride: a sixth of the factorisation's
// time at 50 unknowns): column c's entries below the diagonal add to c's sum and to their rows'.
// NaN or ∞ when an entry is not finite.
double lowerOneNorm(const Eigen::Ref<Eigen::MatrixXd>& A) {
  thread_local Eigen::VectorXd sums;
  const Index n = A.rows();
  sums.setZero(n);
  double norm = 0;
  for (Index c = 0; c < n; ++c) {
    const Index below = n - c - 1;
    sums.segment(c + 1, below) += A.col(c).tail(below).cwiseAbs();
    const double sum = sums(c) + A.col(c).tail(below + 1).lpNorm<1>();
    if (std::isnan(sum) || sum > norm) norm = sum;
    if (std::isnan(norm)) return norm;
  }
  return norm;
}

}  // namespace

SmallCholesky::SmallCholesky(Eigen::Ref<Eigen::MatrixXd> A) : L_(A) {
  const Index size = L_.rows();
  norm_ = lowerOneNorm(L_);
  ok_ = (size <= kSmallCholeskyUnblockedUpTo ? Lower::unblocked(L_) : blockedCholesky(L_)) == -1;
}

double SmallCholesky::rcond() const {
  return choleskyReciprocalCondition(norm_, L_.data(), L_.rows(), L_.outerStride());
}

Eigen::VectorXd SmallCholesky::solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd x = b;
  L_.triangularView<Eigen::Lower>().solveInPlace(x);
  L_.triangularView<Eigen::Lower>().adjoint().solveInPlace(x);
  return x;
}

}  // namespace hermite
