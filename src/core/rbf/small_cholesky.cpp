#include "core/rbf/small_cholesky.h"

#include <algorithm>

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

}  // namespace

SmallCholesky::SmallCholesky(Eigen::Ref<Eigen::MatrixXd> A) : L_(A) {
  const Index size = L_.rows();
  // ‖A‖₁ from the lower triangle, as Eigen's LLT::compute sums it.
  for (Index col = 0; col < size; ++col) {
    const double sum = L_.col(col).tail(size - col).lpNorm<1>() + L_.row(col).head(col).lpNorm<1>();
    norm_ = std::max(norm_, sum);
  }
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
