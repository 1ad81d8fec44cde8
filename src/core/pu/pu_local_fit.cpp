#include "core/pu/pu_local_fit.h"

#include <chrono>
#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/Householder>
#include <Eigen/LU>
#include <Eigen/QR>

#include "core/base/ms_since.h"
#include "core/rbf/small_cholesky.h"

namespace hermite {

namespace {

// Per-thread buffers of the local fits, reused from box to box: fresh allocations of these sizes
// go to mmap and cost page faults on every local fit (about 15 % of a PU fit once).
struct LocalBuffers {
  Eigen::MatrixXd K;  // the system: kernel block or saddle matrix, then its factor
  Eigen::MatrixXd P;  // n × m polynomial rows
  Eigen::VectorXd b;  // n: (0, nᵢ) per sample
};

LocalBuffers& localBuffers() {
  thread_local LocalBuffers buffers;
  return buffers;
}

// The kernel block's lower triangle and diagonal into A (n × n), the polynomial rows into P and
// the right-hand side into b, as assembleHrbf builds them (without its n × n allocation).
template <int Dim>
void assembleLocal(const HermiteSamples<Dim>& sub, const HrbfOptions& options, Eigen::Ref<Eigen::MatrixXd> A,
                   Eigen::Ref<Eigen::MatrixXd> P, Eigen::Ref<Eigen::VectorXd> b) {
  constexpr int B = Dim + 1;
  const int N = sub.size();
  const Points<Dim>& p = sub.points;
  for (int j = 0; j < N; ++j)
    for (int i = j; i < N; ++i)
      A.template block<B, B>(Eigen::Index(i) * B, Eigen::Index(j) * B) = hrbfBlock<Dim>(options.kernel, p.col(i) - p.col(j));
  const double lambda = options.kernel.smoothingSign() * options.smoothing;
  if (lambda != 0) A.diagonal().array() += lambda;
  b.setZero();
  for (int i = 0; i < N; ++i) {
    b.template segment<Dim>(Eigen::Index(i) * B + 1) = sub.normals.col(i);
    if (P.cols() > 0) P.middleRows(Eigen::Index(i) * B, B) = hrbfPolynomialRows<Dim>(options.polynomial, p.col(i));
  }
}

// The solution of one path: x (n), c (m), the 1-norm condition estimate and the path's name.
struct LocalSolution {
  Eigen::VectorXd x, c;
  double condition = 0;
  const char* solver = "";
};

// Accepts a factorisation whose reciprocal condition estimate is above 1e-15 and a finite solution.
bool acceptable(double rcond, const LocalSolution& s) {
  return rcond > 1e-15 && s.x.allFinite() && s.c.allFinite();
}

// cholesky: no polynomial, A positive definite.
bool solveCholesky(Eigen::Ref<Eigen::MatrixXd> A, const Eigen::VectorXd& b, LocalSolution& out) {
  const SmallCholesky llt(A);  // in place, reads the lower triangle
  if (!llt.ok()) return false;
  const double rcond = llt.rcond();  // Eigen's 1-norm estimate, as LAPACK's dpocon
  out.x = llt.solve(b);
  out.c.resize(0);
  out.condition = 1.0 / rcond;
  out.solver = "cholesky";
  return acceptable(rcond, out);
}

// Q = H₀H₁⋯H_{m−1} = I − V T Vᵀ (compact WY form, LAPACK's dlarft): V (n × m) the unit lower
// trapezoidal reflectors of a Householder QR, T (m × m) upper triangular.
struct CompactQ {
  Eigen::MatrixXd V, T;
};

// A vector of at most m entries, on the stack.
using SmallVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxMonomials<3>, 1>;

CompactQ compactQ(const Eigen::HouseholderQR<Eigen::MatrixXd>& qr) {
  const Eigen::Index m = qr.matrixQR().cols();
  CompactQ q;
  q.V = qr.matrixQR();
  for (Eigen::Index j = 0; j < m; ++j) {
    q.V.col(j).head(j).setZero();
    q.V(j, j) = 1.0;
  }
  q.T = Eigen::MatrixXd::Zero(m, m);
  const Eigen::VectorXd& tau = qr.hCoeffs();
  for (Eigen::Index i = 0; i < m; ++i) {
    q.T(i, i) = tau(i);
    if (i == 0) continue;
    const SmallVector w = q.V.leftCols(i).transpose() * q.V.col(i);
    const SmallVector Tw = q.T.topLeftCorner(i, i).triangularView<Eigen::Upper>() * w;
    q.T.col(i).head(i) = -tau(i) * Tw;
  }
  return q;
}

// nullspace-cholesky: A definite with sign `sign` on null(Pᵀ) (pu_local_fit.h). A's lower
// triangle becomes that of B = QᵀAQ = A − W Vᵀ − V Wᵀ with W = Y − ½V(TᵀVᵀY), Y = A V T: one
// symmetric product and a rank-2m update, 4n²m flops in matrix products (applying the m
// reflectors one by one, as vectors, took longer than the Cholesky factorisation itself).
bool solveNullspace(Eigen::Ref<Eigen::MatrixXd> A, const Eigen::Ref<const Eigen::MatrixXd>& P, const Eigen::VectorXd& b,
                    int sign, LocalSolution& out) {
  const Eigen::Index n = A.rows(), m = P.cols(), r = n - m;
  if (r < 1) return false;
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(P);
  const auto R = qr.matrixQR().topLeftCorner(m, m);
  const double rMax = R.diagonal().cwiseAbs().maxCoeff();
  if (!(R.diagonal().cwiseAbs().minCoeff() > 1e-12 * rMax)) return false;  // P rank-deficient
  const CompactQ q = compactQ(qr);
  const Eigen::MatrixXd Y = (A.selfadjointView<Eigen::Lower>() * q.V) * q.T;
  const Eigen::MatrixXd W = Y - 0.5 * q.V * (q.T.transpose() * (q.V.transpose() * Y));
  A.triangularView<Eigen::Lower>() -= W * q.V.transpose();
  A.triangularView<Eigen::Lower>() -= q.V * W.transpose();
  Eigen::Ref<Eigen::MatrixXd> B22 = A.bottomRightCorner(r, r);
  if (sign < 0) B22.triangularView<Eigen::Lower>() *= -1.0;
  const Eigen::VectorXd bq = b - q.V * (q.T.transpose() * (q.V.transpose() * b));  // Qᵀb
  const SmallCholesky llt(B22);  // in place, lower triangle; B₂₁ is untouched
  if (!llt.ok()) return false;
  const double rcond = llt.rcond();
  const Eigen::VectorXd y = llt.solve(double(sign) * bq.tail(r));
  // R c = (Qᵀb)₁ − B₁₂ y with B₁₂ = B₂₁ᵀ.
  out.c = R.triangularView<Eigen::Upper>().solve(bq.head(m) - A.bottomLeftCorner(r, m).transpose() * y);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  z.tail(r) = y;
  out.x = z - q.V * (q.T * (q.V.transpose() * z));  // Q [0; y]
  out.condition = 1.0 / rcond;
  out.solver = "nullspace-cholesky";
  return acceptable(rcond, out);
}

// lu: the whole saddle matrix [A P; Pᵀ 0], built in K from A's lower triangle.
bool solveLu(Eigen::Ref<Eigen::MatrixXd> K, Eigen::Index n, const Eigen::Ref<const Eigen::MatrixXd>& P,
             const Eigen::VectorXd& b, LocalSolution& out) {
  const Eigen::Index m = P.cols();
  K.topLeftCorner(n, n).triangularView<Eigen::StrictlyUpper>() = K.topLeftCorner(n, n).transpose();
  if (m > 0) {
    K.topRightCorner(n, m) = P;
    K.bottomLeftCorner(m, n) = P.transpose();
    K.bottomRightCorner(m, m).setZero();
  }
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + m);
  rhs.head(n) = b;
  Eigen::PartialPivLU<Eigen::Ref<Eigen::MatrixXd>> lu(K);  // in place
  const double rcond = lu.rcond();
  if (!(rcond > 1e-15)) return false;
  const Eigen::VectorXd sol = lu.solve(rhs);
  out.x = sol.head(n);
  out.c = sol.tail(m);
  out.condition = 1.0 / rcond;
  out.solver = "lu";
  return acceptable(rcond, out);
}

}  // namespace

template <int Dim>
HrbfModel<Dim> fitPuLocal(const HermiteSamples<Dim>& sub, const HrbfOptions& options, FitReport& report) {
  const int N = sub.size();
  const int m = monomialCount<Dim>(options.polynomial);
  constexpr int B = Dim + 1;
  const int n = N * B;
  const Kernel& kernel = options.kernel;
  // Options assembleHrbf refuses go there for its message; large systems and explicit solvers too.
  const bool validOptions = N >= 1 && options.smoothing >= 0 && options.smoothing <= kMaxSmoothing &&
                            (!kernel.usesRadius() || kernel.radius > 0);
  if (!validOptions || n + m > kPuInProcessUnknowns || options.solver != SolverChoice::Auto)
    return fitHrbfAbout<Dim>(sub, options, Vec<Dim>::Zero(), &report);
  const auto t0 = std::chrono::steady_clock::now();
  LocalBuffers& buf = localBuffers();
  if (buf.K.rows() < n + m) buf.K.resize(n + m, n + m);
  buf.P.resize(n, m);
  buf.b.resize(n);
  Eigen::Ref<Eigen::MatrixXd> K = buf.K.topLeftCorner(n + m, n + m);
  const auto assemble = [&] { assembleLocal<Dim>(sub, options, K.topLeftCorner(n, n), buf.P, buf.b); };
  const int sign = kernelDefiniteSign(kernel, options.polynomial, options.smoothing);
  LocalSolution s;
  assemble();
  const bool cholesky = sign > 0 && m == 0, nullspace = sign != 0 && m > 0;
  bool solved = false;
  if (cholesky) solved = solveCholesky(K.topLeftCorner(n, n), buf.b, s);
  if (nullspace) solved = solveNullspace(K.topLeftCorner(n, n), buf.P, buf.b, sign, s);
  if (!solved) {
    if (cholesky || nullspace) assemble();  // the failed path overwrote the block
    // Near-singular or non-finite: the LAPACK path decides (pivoted fallbacks, warnings, and a
    // NumericalError only for a failed factorisation — which makes the caller grow the support).
    if (!solveLu(K, n, buf.P, buf.b, s)) return fitHrbfAbout<Dim>(sub, options, Vec<Dim>::Zero(), &report);
  }
  Eigen::VectorXd alpha(N);
  Points<Dim> beta(Dim, N);
  for (int j = 0; j < N; ++j) {
    alpha(j) = s.x(Eigen::Index(j) * B);
    beta.col(j) = s.x.template segment<Dim>(Eigen::Index(j) * B + 1);
  }
  report.solver = s.solver;
  report.nSamples = N;
  report.nUnknowns = n + m;
  report.conditionEstimate = s.condition;
  report.warnings = polynomialOrderWarnings(kernel, options.polynomial);
  if (auto warning = illConditionedWarning(s.condition, report.solver)) report.warnings.push_back(*warning);
  report.fitMs = msSince(t0);
  return HrbfModel<Dim>(kernel, options.polynomial, sub.points, std::move(alpha), std::move(beta), std::move(s.c));
}

template HrbfModel<2> fitPuLocal<2>(const HermiteSamples<2>&, const HrbfOptions&, FitReport&);
template HrbfModel<3> fitPuLocal<3>(const HermiteSamples<3>&, const HrbfOptions&, FitReport&);

}  // namespace hermite
