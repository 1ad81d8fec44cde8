#include "core/rbf/cholesky_solve.h"

#include <algorithm>

#include <cblas.h>

namespace hermite {

namespace {

// Columns per panel: 128 was fastest on a 3 996-unknown factor (64 MB) on this machine; 256 and
// 512 were 10–25 % slower, 0 (plain dpotrs) twice as slow.
constexpr Eigen::Index kPanel = 128;

const double* at(const double* L, Eigen::Index ld, Eigen::Index row, Eigen::Index col) {
  return L + col * ld + row;
}

}  // namespace

void solveWithCholeskyFactor(const double* L, Eigen::Index k, Eigen::Index ld, Eigen::Ref<Eigen::VectorXd> v) {
  if (k <= 0) return;
  const int lda = int(ld);
  double* b = v.data();
  // L y = v, panel by panel from the top: solve the diagonal block, then subtract its
  // contribution from the rows below.
  for (Eigen::Index j = 0; j < k; j += kPanel) {
    const Eigen::Index w = std::min(kPanel, k - j), rest = k - j - w;
    cblas_dtrsv(CblasColMajor, CblasLower, CblasNoTrans, CblasNonUnit, int(w), at(L, ld, j, j), lda, b + j, 1);
    if (rest > 0)
      cblas_dgemv(CblasColMajor, CblasNoTrans, int(rest), int(w), -1.0, at(L, ld, j + w, j), lda, b + j, 1, 1.0,
                  b + j + w, 1);
  }
  // Lᵀ x = y, panel by panel from the bottom: subtract the solved rows below, then solve.
  for (Eigen::Index j = ((k - 1) / kPanel) * kPanel; j >= 0; j -= kPanel) {
    const Eigen::Index w = std::min(kPanel, k - j), rest = k - j - w;
    if (rest > 0)
      cblas_dgemv(CblasColMajor, CblasTrans, int(rest), int(w), -1.0, at(L, ld, j + w, j), lda, b + j + w, 1, 1.0,
                  b + j, 1);
    cblas_dtrsv(CblasColMajor, CblasLower, CblasTrans, CblasNonUnit, int(w), at(L, ld, j, j), lda, b + j, 1);
  }
}

}  // namespace hermite
