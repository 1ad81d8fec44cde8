#include "core/rbf/dense_solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>

#include <cblas.h>
#include <lapacke.h>

#include <Eigen/LU>

#include "core/base/errors.h"
#include "core/base/huge_pages.h"
#include "core/base/memory_check.h"
#include "core/base/threading.h"
#include "core/rbf/cholesky_solve.h"
#include "core/rbf/dense_fit_memory.h"
#include "core/rbf/kept_kernel_matrix.h"
#include "core/rbf/lapack_errors.h"
#include "core/rbf/symmetric_norm.h"

// LAPACK's reverse-communication 1-norm estimator (no LAPACKE wrapper exists for it).
extern "C" void dlacn2_(const int* n, double* v, double* x, int* isgn, double* est, int* kase, int* isave);

namespace hermite {

static_assert(sizeof(lapack_int) == sizeof(int), "DenseLu keeps LAPACK pivots as int");

namespace {

using Index = Eigen::Index;

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

lapack_int toLapack(Index n) { return static_cast<lapack_int>(n); }

// Restores a symmetric matrix whose lower triangle and diagonal were overwritten (by dpotrf or
// the projection) from its untouched upper triangle and a saved copy of the diagonal.
void restoreSymmetric(Eigen::MatrixXd& M, const Eigen::VectorXd& diagonal) {
  M.triangularView<Eigen::StrictlyLower>() = M.transpose().triangularView<Eigen::StrictlyLower>();
  M.diagonal() = diagonal;
}

// Records the wall-clock time since the previous lap under a phase name.
class PhaseClock {
 public:
  explicit PhaseClock(std::vector<std::pair<std::string, double>>& out) : out_(out) {}
  void lap(const char* name) {
    const auto now = std::chrono::steady_clock::now();
    out_.emplace_back(name, std::chrono::duration<double, std::milli>(now - last_).count());
    last_ = now;
  }

 private:
  std::vector<std::pair<std::string, double>>& out_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

struct Factorised {
  bool ok = false;
  std::string failure;  // why the factorisation failed
  double rcond = 0;
};

// A factorisation whose LAPACK calls all returned: ok unless LAPACK reported an illegal argument
// through its error handler (lapack_errors.h), which then becomes the failure.
Factorised checked(Factorised out) {
  if (auto error = takeLapackError()) {
    out.ok = false;
    out.failure = "LAPACK rejected an argument (" + *error + ")";
    return out;
  }
  out.ok = true;
  return out;
}

// The factorisations in panels of kPanel columns, polled for cancellation between calls that each
// stay under about 50 ms on this machine (docs/performance.md): the trailing updates run in slabs of
// kSlab columns. Used when a fit carries a cancel token (the GUI); the command line calls LAPACK.
constexpr lapack_int kPanel = 256;
constexpr lapack_int kSlab = 1024;

// Lower Cholesky of the k × k block at M (leading dimension ld), right-looking: the diagonal block
// by dpotrf, the panel below it by a triangular solve, the trailing lower triangle by dsyrk/dgemm.
// Returns dpotrf's info for the whole matrix (0, or the 1-based index of the failing pivot).
lapack_int cancellableCholesky(double* M, lapack_int k, lapack_int ld, const CancelToken* cancel) {
  for (lapack_int j = 0; j < k; j += kPanel) {
    throwIfCancelled(cancel);
    const lapack_int b = std::min(kPanel, k - j), rest = k - j - b;
    double* D = M + std::size_t(j) * ld + j;
    const lapack_int info = LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'L', b, D, ld);
    if (info != 0) return info > 0 ? info + j : info;
    if (rest == 0) break;
    double* below = D + b;  // rows j + b …, columns j … j + b
    cblas_dtrsm(CblasColMajor, CblasRight, CblasLower, CblasTrans, CblasNonUnit, rest, b, 1.0, D, ld, below, ld);
    double* trailing = M + std::size_t(j + b) * ld + j + b;
    for (lapack_int c = 0; c < rest; c += kSlab) {
      throwIfCancelled(cancel);
      const lapack_int w = std::min(kSlab, rest - c);
      double* slab = trailing + std::size_t(c) * ld + c;
      cblas_dsyrk(CblasColMajor, CblasLower, CblasNoTrans, w, b, -1.0, below + c, ld, 1.0, slab, ld);
      if (rest - c - w > 0)
        cblas_dgemm(CblasColMajor, CblasNoTrans, CblasTrans, rest - c - w, w, b, -1.0, below + c + w, ld, below + c, ld,
                    1.0, slab + w, ld);
    }
  }
  return 0;
}

// LU with partial pivoting of the n × n matrix A (leading dimension n), right-looking: each panel
// by dgetrf, its row interchanges applied left and right, U₁₂ by a triangular solve, the trailing
// block by dgemm. Returns dgetrf's info for the whole matrix (the first exactly zero pivot).
lapack_int cancellableLu(double* A, lapack_int n, lapack_int* ipiv, const CancelToken* cancel) {
  lapack_int first = 0;
  for (lapack_int j = 0; j < n; j += kPanel) {
    throwIfCancelled(cancel);
    const lapack_int b = std::min(kPanel, n - j), rest = n - j - b;
    double* D = A + std::size_t(j) * n + j;
    const lapack_int info = LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, n - j, b, D, n, ipiv + j);
    if (info < 0) return info;
    if (info > 0 && first == 0) first = info + j;
    for (lapack_int i = j; i < j + b; ++i) ipiv[i] += j;
    if (j > 0) LAPACKE_dlaswp_work(LAPACK_COL_MAJOR, j, A, n, j + 1, j + b, ipiv, 1);
    if (rest == 0) break;
    double* right = A + std::size_t(j + b) * n;
    LAPACKE_dlaswp_work(LAPACK_COL_MAJOR, rest, right, n, j + 1, j + b, ipiv, 1);
    cblas_dtrsm(CblasColMajor, CblasLeft, CblasLower, CblasNoTrans, CblasUnit, b, rest, 1.0, D, n, right + j, n);
    for (lapack_int c = 0; c < rest; c += kSlab) {
      throwIfCancelled(cancel);
      const lapack_int w = std::min(kSlab, rest - c);
      double* slab = right + std::size_t(c) * n;
      cblas_dgemm(CblasColMajor, CblasNoTrans, CblasNoTrans, rest, w, b, -1.0, D + b, n, slab + j, n, 1.0, slab + j + b, n);
    }
  }
  return first;
}

// rcond as LAPACK's ?con defines it, 1 / (‖M‖₁ · est ‖M⁻¹‖₁), with the estimate made by
// dlacn2 through the factors' own solves (`solve`: v ← M⁻¹v, M symmetric). LAPACK's ?con make
// the same estimate through dlatrs, a scaled unblocked triangular solve several times slower
// than the blocked solves (docs/performance.md). 0 when the estimate is not finite.
double reciprocalCondition(double anorm, Index n, const std::function<void(Eigen::VectorXd&)>& solve) {
  const double inverseNorm = symmetricInverseNormEstimate(n, solve);
  return anorm > 0 && inverseNorm > 0 && std::isfinite(inverseNorm) ? 1.0 / (anorm * inverseNorm) : 0.0;
}

// Cholesky of sign·M in place, M = the k × k block at `M` with leading dimension `ld` (lower
// triangle only; the upper triangle is left untouched so a failure can be undone). Solves
// sign·M y = sign·rhs in place of rhs. `knownNorm` is M's 1-norm when the caller has it (a
// negative value: read it here, in the pass that also finds non-finite entries).
Factorised choleskySolve(double* M, lapack_int k, lapack_int ld, double sign, Eigen::Ref<Eigen::VectorXd> rhs,
                         PhaseClock& clock, const CancelToken* cancel, bool estimateCondition = true,
                         double knownNorm = -1) {
  Factorised out;
  if (k == 0) {  // nothing to solve (LAPACK would reject the empty right-hand side's stride)
    out.ok = true;
    out.rcond = 1;
    return out;
  }
  if (sign < 0)
    for (lapack_int j = 0; j < k; ++j)
      for (lapack_int i = j; i < k; ++i) M[size_t(j) * ld + i] = -M[size_t(j) * ld + i];
  const double anorm = knownNorm >= 0 ? knownNorm : lowerSymmetricOneNorm(M, k, ld);
  if (!std::isfinite(anorm)) {
    clock.lap("factor");
    out.failure = "Cholesky: the matrix has non-finite entries (an overflow, e.g. in the projection)";
    return out;
  }
  // The _work form: LAPACKE's own NaN scan would read the triangle once more.
  const lapack_int info =
      cancel ? cancellableCholesky(M, k, ld, cancel) : LAPACKE_dpotrf_work(LAPACK_COL_MAJOR, 'L', k, M, ld);
  clock.lap("factor");
  if (info != 0) {
    out.failure = info > 0 ? "Cholesky: the matrix is not positive definite (pivot " + std::to_string(info) +
                                 " of " + std::to_string(k) + ")"
                           : "Cholesky: invalid argument " + std::to_string(-info);
    return out;
  }
  if (estimateCondition) {
    out.rcond = reciprocalCondition(anorm, k, [&](Eigen::VectorXd& v) { solveWithCholeskyFactor(M, k, ld, v); });
    clock.lap("condition");
  }
  if (sign < 0) rhs *= -1.0;
  solveWithCholeskyFactor(M, k, ld, rhs);
  return checked(out);
}

// Replaces the lower triangle of the symmetric A (n × n, read from its lower triangle) by that of
// B = Qᵀ A Q, Q = I − V T Vᵀ from the QR of P, leaving the strict upper triangle untouched.
// With Y = A V T and W = Tᵀ Vᵀ Y (symmetric): B = A − Z Vᵀ − V Zᵀ, Z = Y − ½ V W — one symmetric
// product and one rank-2m update of the lower triangle, as in LAPACK's dsytrd.
void projectLower(Eigen::MatrixXd& A, const Eigen::MatrixXd& QR, const Eigen::VectorXd& tau) {
  const lapack_int n = toLapack(A.rows()), m = toLapack(QR.cols());
  Eigen::MatrixXd V = QR.triangularView<Eigen::UnitLower>();
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(m, m);
  LAPACKE_dlarft(LAPACK_COL_MAJOR, 'F', 'C', n, m, V.data(), n, tau.data(), T.data(), m);
  Eigen::MatrixXd AV(n, m);
  cblas_dsymm(CblasColMajor, CblasLeft, CblasLower, n, m, 1.0, A.data(), n, V.data(), n, 0.0, AV.data(), n);
  const Eigen::MatrixXd Y = AV * T.triangularView<Eigen::Upper>();
  const Eigen::MatrixXd W = T.triangularView<Eigen::Upper>().transpose() * (V.transpose() * Y);
  const Eigen::MatrixXd Z = Y - 0.5 * V * W;
  cblas_dsyr2k(CblasColMajor, CblasLower, CblasNoTrans, n, m, -1.0, Z.data(), n, V.data(), n, 1.0, A.data(), n);
}

// Full saddle matrix K = [[A, P], [Pᵀ, 0]] (both triangles).
Eigen::MatrixXd saddleMatrix(const Eigen::MatrixXd& A, const Eigen::MatrixXd& P) {
  const Index n = A.rows(), m = P.cols();
  Eigen::MatrixXd K(n + m, n + m);
  adviseHugePages(K.data(), sizeof(double) * std::size_t(K.size()));
  K.topLeftCorner(n, n) = A;
  K.topRightCorner(n, m) = P;
  K.bottomLeftCorner(m, n) = P.transpose();
  K.bottomRightCorner(m, m).setZero();
  return K;
}

Factorised ldltSolve(Eigen::MatrixXd& K, Eigen::VectorXd& rhs, PhaseClock& clock) {
  Factorised out;
  takeLapackError();  // a failed earlier path reported its own error through info
  const lapack_int n = toLapack(K.rows());
  std::vector<lapack_int> ipiv(n);
  const double anorm = lowerSymmetricOneNorm(K.data(), n, n);
  const lapack_int info = LAPACKE_dsytrf(LAPACK_COL_MAJOR, 'L', n, K.data(), n, ipiv.data());
  clock.lap("factor");
  if (info != 0) {
    out.failure = info > 0 ? "symmetric-indefinite LDLᵀ: D(" + std::to_string(info) + "," +
                                 std::to_string(info) + ") is exactly zero (singular)"
                           : "LDLᵀ: invalid argument " + std::to_string(-info);
    return out;
  }
  out.rcond = reciprocalCondition(anorm, n, [&](Eigen::VectorXd& v) {
    LAPACKE_dsytrs_work(LAPACK_COL_MAJOR, 'L', n, 1, K.data(), n, ipiv.data(), v.data(), n);
  });
  clock.lap("condition");
  LAPACKE_dsytrs_work(LAPACK_COL_MAJOR, 'L', n, 1, K.data(), n, ipiv.data(), rhs.data(), n);
  return checked(out);
}

Factorised luSolve(Eigen::MatrixXd& K, Eigen::VectorXd& rhs, PhaseClock& clock, const CancelToken* cancel) {
  Factorised out;
  takeLapackError();  // a failed earlier path reported its own error through info
  const lapack_int n = toLapack(K.rows());
  std::vector<lapack_int> ipiv(n);
  // K is symmetric (the saddle matrix), so its lower triangle gives the 1-norm; K's entries are
  // finite (solveSaddle checks A, P and b), so dgetrf goes without LAPACKE's NaN scan.
  const double anorm = lowerSymmetricOneNorm(K.data(), n, n);
  const lapack_int info = cancel ? cancellableLu(K.data(), n, ipiv.data(), cancel)
                                 : LAPACKE_dgetrf_work(LAPACK_COL_MAJOR, n, n, K.data(), n, ipiv.data());
  clock.lap("factor");
  if (info != 0) {
    out.failure = info > 0 ? "LU: U(" + std::to_string(info) + "," + std::to_string(info) +
                                 ") is exactly zero (the system is singular)"
                           : "LU: invalid argument " + std::to_string(-info);
    return out;
  }
  out.rcond = reciprocalCondition(anorm, n, [&](Eigen::VectorXd& v) {  // K is symmetric: K⁻ᵀ = K⁻¹
    LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', n, 1, K.data(), n, ipiv.data(), v.data(), n);
  });
  clock.lap("condition");
  LAPACKE_dgetrs_work(LAPACK_COL_MAJOR, 'N', n, 1, K.data(), n, ipiv.data(), rhs.data(), n);
  return checked(out);
}

// QR of P (n × m) in place, with a rank check: the polynomial term must be determined by the
// data, otherwise the saddle system is singular whatever the kernel.
void factorPolynomialBlock(Eigen::MatrixXd& QR, Eigen::VectorXd& tau) {
  const lapack_int n = toLapack(QR.rows()), m = toLapack(QR.cols());
  if (n < m)
    throw NumericalError("singular system: the samples do not determine the polynomial term (" + std::to_string(m) +
                         " polynomial coefficients but only " + std::to_string(n) +
                         " conditions; use a lower polynomial degree or more samples)");
  tau.resize(m);
  LAPACKE_dgeqrf(LAPACK_COL_MAJOR, n, m, QR.data(), n, tau.data());
  const Eigen::VectorXd diag = QR.topLeftCorner(m, m).diagonal().cwiseAbs();
  const double biggest = diag.maxCoeff();
  for (lapack_int k = 0; k < m; ++k) {
    if (!(diag(k) > 1e-12 * biggest)) {
      throw NumericalError("singular system: the samples do not determine the polynomial term (column " +
                           std::to_string(k) + " of the polynomial block is dependent on the others; "
                           "use a lower polynomial degree or more, non-degenerate samples)");
    }
  }
}

// Applies Q or Qᵀ (from factorPolynomialBlock) to M from the left ('L') or right ('R').
void applyQ(const Eigen::MatrixXd& QR, const Eigen::VectorXd& tau, char side, char trans, Eigen::Ref<Eigen::MatrixXd> M) {
  LAPACKE_dormqr(LAPACK_COL_MAJOR, side, trans, toLapack(M.rows()), toLapack(M.cols()), toLapack(QR.cols()),
                 QR.data(), toLapack(QR.rows()), tau.data(), M.data(), toLapack(M.outerStride()));
}

// Copies the lower triangle onto the upper one, in 64 × 64 tiles (cache- and TLB-friendly),
// in parallel over tile columns.
void mirrorLowerToUpper(Eigen::MatrixXd& M) {
  const Index n = M.rows();
  constexpr Index kTile = 64;
  const Index tiles = (n + kTile - 1) / kTile;
#pragma omp parallel for schedule(dynamic, 1)
  for (Index tj = 0; tj < tiles; ++tj) {
    for (Index ti = tj; ti < tiles; ++ti) {
      const Index j0 = tj * kTile, i0 = ti * kTile;
      const Index j1 = std::min(n, j0 + kTile), i1 = std::min(n, i0 + kTile);
      for (Index i = i0; i < i1; ++i)
        for (Index j = j0; j < std::min(j1, i); ++j) M(j, i) = M(i, j);
    }
  }
}

bool isCholeskyPath(SolverChoice path) {
  return path == SolverChoice::Cholesky || path == SolverChoice::NullspaceCholesky ||
         path == SolverChoice::ProjectedCholesky;
}

// Undoes a failed Cholesky path's writes to A's lower triangle and diagonal: through the system's
// assembleLower (then mirrored for the LU that follows), else from the untouched upper triangle
// and the saved diagonal.
void restoreAfterCholesky(SaddleSystem& sys, const Eigen::VectorXd& diagonal) {
  if (sys.assembleLower) {
    sys.assembleLower(sys.A);
    mirrorLowerToUpper(sys.A);
  } else {
    restoreSymmetric(sys.A, diagonal);
  }
}

// The factors of the projected-cholesky path (dense_solver.h) and its solve. With C = QR,
// B = QᵀAQ = [[B₁₁, B₂₁ᵀ], [B₂₁, B₂₂]] (q and n − q rows), B₂₂ = sign·LLᵀ:
//   A x = b  ⇔  B z = g = Qᵀb, x = Qz;  z₁ = S⁻¹(g₁ − B₂₁ᵀ B₂₂⁻¹ g₂),  z₂ = B₂₂⁻¹ g₂ − W z₁,
// with W = B₂₂⁻¹ B₂₁ (n − q × q) and the Schur complement S = B₁₁ − B₂₁ᵀ W (q × q).
struct ProjectedFactors {
  Eigen::MatrixXd QR;
  Eigen::VectorXd tau;
  const double* L = nullptr;  // the Cholesky factor of sign·B₂₂, inside the system's A
  lapack_int ld = 0;
  double sign = 1;
  Eigen::MatrixXd B21, W;
  Eigen::FullPivLU<Eigen::MatrixXd> schur;

  Index n() const { return QR.rows(); }
  Index q() const { return QR.cols(); }

  // v ← B₂₂⁻¹ v for a block of n − q rows.
  void solveTrailing(Eigen::Ref<Eigen::MatrixXd> v) const {
    if (v.cols() == 1)
      solveWithCholeskyFactor(L, v.rows(), ld, v.col(0));
    else
      LAPACKE_dpotrs_work(LAPACK_COL_MAJOR, 'L', toLapack(v.rows()), toLapack(v.cols()), L, ld, v.data(),
                          toLapack(v.outerStride()));
    v *= sign;
  }

  // v ← A⁻¹ v.
  void solve(Eigen::VectorXd& v) const {
    applyQ(QR, tau, 'L', 'T', v);
    Eigen::MatrixXd y = v.tail(n() - q());
    solveTrailing(y);
    const Eigen::VectorXd z1 = schur.solve(Eigen::VectorXd(v.head(q()) - B21.transpose() * y));
    v.head(q()) = z1;
    v.tail(n() - q()) = y - W * z1;
    applyQ(QR, tau, 'L', 'N', v);
  }
};

// The projected-cholesky path on the system's A (m = 0; read from its lower triangle). On
// success x = A⁻¹ b and the factors are returned; on failure A's lower triangle and diagonal are
// overwritten (restoreAfterCholesky undoes it) and `failure` says why.
Factorised projectedCholeskySolve(SaddleSystem& sys, double aNorm, Eigen::VectorXd& x, PhaseClock& clock) {
  Factorised out;
  const Index n = sys.A.rows();
  ProjectedFactors F;
  F.QR = sys.definiteOn;
  try {
    factorPolynomialBlock(F.QR, F.tau);
  } catch (const NumericalError&) {
    out.failure = "projected Cholesky: the samples do not determine the kernel's polynomial";
    return out;
  }
  const Index q = F.q();
  clock.lap("qr");
  projectLower(sys.A, F.QR, F.tau);
  clock.lap("project");
  throwIfCancelled(sys.cancel);
  F.sign = sys.definiteOnSign < 0 ? -1.0 : 1.0;
  F.ld = toLapack(n);
  double* B22 = sys.A.data() + q * n + q;
  Eigen::VectorXd g = sys.b;
  applyQ(F.QR, F.tau, 'L', 'T', g);
  Eigen::VectorXd y = g.tail(n - q);
  out = choleskySolve(B22, toLapack(n - q), F.ld, F.sign, y, clock, sys.cancel, false);
  if (!out.ok) {
    out.failure = "projected " + out.failure;
    return out;
  }
  F.L = B22;
  F.B21 = sys.A.block(q, 0, n - q, q);
  F.W = F.B21;
  F.solveTrailing(F.W);
  const Eigen::MatrixXd S =
      Eigen::MatrixXd(sys.A.topLeftCorner(q, q).selfadjointView<Eigen::Lower>()) - F.B21.transpose() * F.W;
  F.schur.compute(S);
  if (!F.schur.isInvertible()) {
    out.ok = false;
    out.failure = "projected Cholesky: the Schur complement on the kernel's polynomial is singular";
    return out;
  }
  x = sys.b;
  F.solve(x);
  clock.lap("solve");
  // 1-norm condition of A itself: ‖A‖₁ times the Hager–Higham estimate of ‖A⁻¹‖₁.
  out.rcond = reciprocalCondition(aNorm, n, [&F](Eigen::VectorXd& v) { F.solve(v); });
  clock.lap("condition");
  return out;
}

}  // namespace

std::string_view solverName(SolverChoice s) { return nameIn<SolverChoice>(kSolverChoiceNames, s); }

SolverChoice parseSolverChoice(std::string_view name) {
  if (const auto value = valueIn<SolverChoice>(kSolverChoiceNames, name)) return *value;
  throw InputError("unknown solver '" + std::string(name) + "', expected one of: " +
                   namesIn<SolverChoice>(kSolverChoiceNames));
}

SolverChoice plannedSolverPath(SolverChoice choice, Eigen::Index m, int definiteSign, bool projectable) {
  const bool canProject = projectable && m == 0 && definiteSign == 0;
  if (choice == SolverChoice::Auto) {
    if (definiteSign != 0) return m == 0 ? SolverChoice::Cholesky : SolverChoice::NullspaceCholesky;
    return canProject ? SolverChoice::ProjectedCholesky : SolverChoice::Lu;
  }
  if (choice == SolverChoice::ProjectedCholesky && !canProject) return SolverChoice::Lu;
  if (choice == SolverChoice::Cholesky && m > 0) return SolverChoice::NullspaceCholesky;
  if (choice == SolverChoice::NullspaceCholesky && m == 0) return SolverChoice::Cholesky;
  return choice;
}

namespace {

// The nullspace-cholesky path: the lower triangle of A becomes that of B = Qᵀ A Q, whose trailing
// (n − m) block is Zᵀ A Z with Z spanning null(Pᵀ); the unknowns x = Q [0; y] satisfy Pᵀx = 0 by
// construction. Fills out.x and out.c on success.
Factorised nullspaceCholeskySolve(SaddleSystem& sys, const Eigen::MatrixXd& QR, const Eigen::VectorXd& tau,
                                  double sign, PhaseClock& clock, SaddleSolution& out) {
  const Index n = sys.A.rows(), m = sys.P.cols();
  projectLower(sys.A, QR, tau);
  clock.lap("project");
  throwIfCancelled(sys.cancel);
  Eigen::VectorXd bq = sys.b;
  applyQ(QR, tau, 'L', 'T', bq);
  Eigen::VectorXd y = bq.tail(n - m);
  Factorised fact =
      choleskySolve(sys.A.data() + m * n + m, toLapack(n - m), toLapack(n), sign, y, clock, sys.cancel);
  if (!fact.ok) return fact;
  // R c = (Qᵀ b)₁ − B₁₂ y, with B₁₂ = B₂₁ᵀ from the (untouched by dpotrf) lower part.
  const Eigen::VectorXd rhs = bq.head(m) - sys.A.block(m, 0, n - m, m).transpose() * y;
  out.c = QR.topLeftCorner(m, m).triangularView<Eigen::Upper>().solve(rhs);
  out.x = Eigen::VectorXd::Zero(n);
  out.x.tail(n - m) = y;
  applyQ(QR, tau, 'L', 'N', out.x);
  return fact;
}

// Runs one of the Cholesky paths (cholesky, nullspace-cholesky, projected-cholesky). On success
// out.x, out.c, out.solver and out.factorFlops are set; on failure A is restored for the LU that
// follows and `failure` says why.
Factorised choleskyPathSolve(SaddleSystem& sys, SolverChoice path, const Eigen::MatrixXd& QR,
                             const Eigen::VectorXd& tau, double aNorm, PhaseClock& clock, SaddleSolution& out) {
  const Index n = sys.A.rows(), m = sys.P.cols();
  const double sign = sys.definiteSign < 0 ? -1.0 : 1.0;
  const Eigen::VectorXd diagonal = sys.A.diagonal();  // restoreAfterCholesky's copy
  Factorised fact;
  Index factorised = n;
  if (path == SolverChoice::Cholesky) {
    out.x = sys.b;
    fact = choleskySolve(sys.A.data(), toLapack(n), toLapack(n), sign, out.x, clock, sys.cancel, true, aNorm);
    out.c.resize(0);
  } else if (path == SolverChoice::NullspaceCholesky) {
    fact = nullspaceCholeskySolve(sys, QR, tau, sign, clock, out);
    factorised = n - m;
  } else {
    fact = projectedCholeskySolve(sys, aNorm, out.x, clock);
    out.c.resize(0);
    factorised = n - sys.definiteOn.cols();
  }
  if (!fact.ok) {
    restoreAfterCholesky(sys, diagonal);
    return fact;
  }
  out.solver = std::string(solverName(path));
  out.factorFlops = factorisationFlops(SolverChoice::Cholesky, factorised);
  return fact;
}

// The pivoted paths (ldlt, with LU as its fallback, and lu) on the whole saddle matrix
// [[A, P], [Pᵀ, 0]]; `choice` becomes lu when ldlt falls back. Sets out.x, out.c, out.solver and
// out.factorFlops, or throws NumericalError for a singular system.
Factorised pivotedSolve(SaddleSystem& sys, SolverChoice& choice, PhaseClock& clock, SaddleSolution& out) {
  const Index n = sys.A.rows(), m = sys.P.cols();
  // The copies made here (the saddle matrix when m > 0, the one kept for the LU fallback of
  // ldlt) on top of A: sized before they are made, also when a Cholesky path fell back.
  const std::uint64_t copies = (m > 0 ? 1u : 0u) + (choice == SolverChoice::Ldlt ? 1u : 0u);
  checkMemory({saturatingProduct({copies, std::uint64_t(n + m), std::uint64_t(n + m), sizeof(double)}),
               "the " + std::string(solverName(choice)) + " factorisation of " + std::to_string(n + m) +
                   " unknowns (" + std::to_string(copies) + " more matrices of that size)"},
              kDenseFitRemedy);
  throwIfCancelled(sys.cancel);
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
  rhs.head(n) = sys.b;
  Eigen::MatrixXd K = m > 0 ? saddleMatrix(sys.A, sys.P) : std::move(sys.A);
  Factorised fact;
  if (choice == SolverChoice::Ldlt) {
    Eigen::MatrixXd Kcopy = K;  // kept for the LU fallback
    Eigen::VectorXd r = rhs;
    fact = ldltSolve(K, r, clock);
    if (fact.ok) {
      out.solver = "ldlt";
      out.factorFlops = factorisationFlops(SolverChoice::Ldlt, n + m);
      rhs = r;
    } else {
      out.warnings.push_back(fact.failure + "; fell back to LU with partial pivoting");
      K = std::move(Kcopy);
      choice = SolverChoice::Lu;
    }
  }
  if (choice == SolverChoice::Lu) {
    fact = luSolve(K, rhs, clock, sys.cancel);
    if (!fact.ok) throw NumericalError("singular system: " + fact.failure);
    out.solver = "lu";
    out.factorFlops = factorisationFlops(SolverChoice::Lu, n + m);
  }
  out.x = rhs.head(n);
  out.c = rhs.tail(m);
  return fact;
}

}  // namespace

SaddleSolution solveSaddle(SaddleSystem sys, SolverChoice choice) {
  const Index n = sys.A.rows(), m = sys.P.cols();
  if (sys.A.cols() != n || sys.P.rows() != n || sys.b.size() != n)
    throw NumericalError("solveSaddle: inconsistent shapes");
  SaddleSolution out;
  PhaseClock clock(out.phaseMs);
  takeLapackError();  // a stale record from an earlier call on this thread is not ours
  const bool projectable = sys.definiteOn.cols() > 0 && sys.definiteOnSign != 0;
  // The Cholesky paths read A's lower triangle only; the upper is written only as the copy a
  // failed factorisation restores from, unnecessary when A can be rebuilt.
  if (!(sys.assembleLower && isCholeskyPath(plannedSolverPath(choice, m, sys.definiteSign, projectable))))
    mirrorLowerToUpper(sys.A);
  // ‖A‖₁ from its lower triangle, in the pass that also finds non-finite entries.
  const double aNorm = lowerSymmetricOneNorm(sys.A.data(), n, n);
  if (!std::isfinite(aNorm) || !sys.P.allFinite() || !sys.b.allFinite())
    throw NumericalError("the system has non-finite entries (kernel values overflow for this radius?)");
  clock.lap("prepare");
  throwIfCancelled(sys.cancel);
  // Fewer BLAS threads while other processes keep cores busy; above 2 000 unknowns the
  // factorisation takes tens of milliseconds or more.
  const BlasThreadsForLoad blasThreads(n + m >= 2000);

  Eigen::MatrixXd QR;
  Eigen::VectorXd tau;
  if (m > 0) {
    QR = sys.P;
    factorPolynomialBlock(QR, tau);
    clock.lap("qr");
  }
  if (choice == SolverChoice::Cholesky && m > 0)
    out.warnings.push_back("cholesky needs a system without polynomial term; using nullspace-cholesky");
  choice = plannedSolverPath(choice, m, sys.definiteSign, projectable);

  Factorised fact;
  if (isCholeskyPath(choice)) {
    fact = choleskyPathSolve(sys, choice, QR, tau, aNorm, clock, out);
    if (!fact.ok) {
      out.warnings.push_back(fact.failure + "; fell back to LU with partial pivoting");
      choice = SolverChoice::Lu;
    }
  }
  if (choice == SolverChoice::Ldlt || choice == SolverChoice::Lu) fact = pivotedSolve(sys, choice, clock, out);

  clock.lap("solve");
  out.conditionEstimate = fact.rcond > 0 ? 1.0 / fact.rcond : std::numeric_limits<double>::infinity();
  if (!out.x.allFinite() || !out.c.allFinite())
    throw NumericalError("the solution is not finite (solver " + out.solver + ", condition estimate " +
                         fmt(out.conditionEstimate) + ")");
  if (auto warning = illConditionedWarning(out.conditionEstimate, out.solver)) out.warnings.push_back(*warning);
  if (sys.keepMatrix) keepKernelMatrix(std::move(sys.A));  // empty when LU took it over (m = 0)
  return out;
}

double factorisationFlops(SolverChoice path, Eigen::Index k) {
  const double n = double(k);
  return (path == SolverChoice::Lu ? 2.0 : 1.0) * n * n * n / 3.0;
}

double factorMs(const SaddleSolution& solution) {
  double ms = 0;
  for (const auto& [phase, t] : solution.phaseMs)
    if (phase == "factor") ms = t;
  return ms;
}

std::optional<std::string> illConditionedWarning(double conditionEstimate, std::string_view solver) {
  if (!(conditionEstimate > kIllConditionedEstimate)) return std::nullopt;
  return "ill-conditioned system: condition estimate " + fmt(conditionEstimate) + " (" + std::string(solver) +
         "); expect lost digits in the coefficients";
}

Eigen::MatrixXd saddleMatrix(const SaddleSystem& system) {
  Eigen::MatrixXd A = system.A;
  mirrorLowerToUpper(A);
  if (!A.allFinite() || !system.P.allFinite())
    throw NumericalError("the system has non-finite entries (kernel values overflow for this radius?)");
  return saddleMatrix(A, system.P);
}

DenseLu::DenseLu(Eigen::MatrixXd K) : lu_(std::move(K)) {
  if (lu_.rows() != lu_.cols()) throw NumericalError("LU: the matrix is not square");
  if (!lu_.allFinite()) throw NumericalError("LU: the matrix has non-finite entries");
  const lapack_int n = toLapack(lu_.rows());
  pivots_.resize(std::size_t(n));
  if (n == 0) return;
  const lapack_int info = LAPACKE_dgetrf(LAPACK_COL_MAJOR, n, n, lu_.data(), n, pivots_.data());
  if (info != 0)
    throw NumericalError(info > 0 ? "singular system: LU pivot U(" + std::to_string(info) + "," +
                                        std::to_string(info) + ") is exactly zero"
                                  : "LU: invalid argument " + std::to_string(-info));
}

// The solves run in Eigen, not dgetrs: a drag calls them every frame with a few columns, where
// LAPACKE's NaN scan of the whole factor (n² per call) and OpenBLAS's worker threads — which
// then spin in sched_yield for a while, taking a core from the renderer — cost more than the
// solve itself.
template <class Rhs>
void solveWithFactors(const Eigen::MatrixXd& lu, const std::vector<int>& pivots, Rhs& rhs) {
  if (rhs.rows() != lu.rows()) throw NumericalError("LU solve: right-hand side of the wrong size");
  for (Index k = 0; k < lu.rows(); ++k) {  // the row interchanges of dgetrf, in order (1-based)
    const Index p = pivots[std::size_t(k)] - 1;
    if (p != k) rhs.row(k).swap(rhs.row(p));
  }
  lu.triangularView<Eigen::UnitLower>().solveInPlace(rhs);
  lu.triangularView<Eigen::Upper>().solveInPlace(rhs);
}

void DenseLu::solveInPlace(Eigen::MatrixXd& rhs) const { solveWithFactors(lu_, pivots_, rhs); }

void DenseLu::solveInPlace(Eigen::VectorXd& rhs) const { solveWithFactors(lu_, pivots_, rhs); }

double symmetricInverseNormEstimate(Eigen::Index n, const std::function<void(Eigen::VectorXd&)>& solve) {
  if (n <= 0) return 0;
  const int size = toLapack(n);
  Eigen::VectorXd v(n), x(n);
  std::vector<int> sign(static_cast<std::size_t>(n));
  int isave[3] = {0, 0, 0};
  int kase = 0;
  double estimate = 0;
  // kase 1 asks for M⁻¹x, kase 2 for M⁻ᵀx: the same solve for a symmetric M. The estimator
  // stops by itself after at most 5 iterations.
  for (;;) {
    dlacn2_(&size, v.data(), x.data(), sign.data(), &estimate, &kase, isave);
    if (kase == 0) break;
    solve(x);
  }
  return estimate;
}

}  // namespace hermite
