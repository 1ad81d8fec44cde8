#include "core/rbf/hrbf_bordered_refit.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "core/base/errors.h"
#include "core/base/memory_check.h"
#include "core/base/ms_since.h"
#include "core/rbf/dense_fit_memory.h"

namespace hermite {

namespace {

std::string shortNumber(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Residual tolerance of a bordered solve, relative to ‖K‖∞‖x‖∞ + ‖b‖∞: LU's backward error is
// a small multiple of n·2⁻⁵³ of that scale; well above it only when the Schur route lost
// accuracy (K_RR much worse conditioned than K), and then the caller refits from scratch.
constexpr double kResidualTolerance = 1e-9;

}  // namespace

template <int Dim>
HrbfBorderedRefit<Dim>::HrbfBorderedRefit(const HermiteSamples<Dim>& samples, const HrbfOptions& options, int moved)
    : samples_(samples), options_(options), moved_(moved) {
  const int N = samples.size();
  if (N < 2) throw InputError("HRBF drag refit: needs at least 2 samples (got " + std::to_string(N) + ")");
  if (moved < 0 || moved >= N)
    throw InputError("HRBF drag refit: sample " + std::to_string(moved) + " is not one of the " +
                     std::to_string(N) + " samples");
  // Peak: the kernel block, K_RR and its LU, 3 square matrices of the unknowns left.
  const std::uint64_t unknowns = std::uint64_t(N - 1) * B + monomialCount<Dim>(options.polynomial);
  checkMemory({saturatingProduct({3, unknowns, unknowns, sizeof(double)}),
               "the drag refit's kept factorisation of " + std::to_string(unknowns) +
                   " unknowns (3 matrices of that size squared)"},
              kDenseFitRemedy);
  const SaddleSystem system = assembleHrbf(withoutSample(samples, moved), options);
  Krr_ = saddleMatrix(system);
  bR_ = Eigen::VectorXd::Zero(Krr_.rows());
  bR_.head(system.b.size()) = system.b;
  lu_.emplace(Krr_);
  zR_ = bR_;
  lu_->solveInPlace(zR_);
  krrColumnSums_ = Krr_.cwiseAbs().colwise().sum().transpose();
}

template <int Dim>
void HrbfBorderedRefit<Dim>::solveBordered(const Border& Kri, const Eigen::PartialPivLU<Block>& schur, const Border& Y,
                                        Eigen::VectorXd& rhsR, Eigen::Matrix<double, B, 1>& rhsI) const {
  lu_->solveInPlace(rhsR);                                                    // y = K_RR⁻¹ r_R
  rhsI = schur.solve((rhsI - Kri.transpose() * rhsR).eval());                 // x_I = S⁻¹ (r_I − K_IR y)
  rhsR -= Y * rhsI;                                                            // x_R = y − Y x_I
}

template <int Dim>
HrbfModel<Dim> HrbfBorderedRefit<Dim>::fit(const Vec<Dim>& point, const Vec<Dim>& normal, FitReport* report) const {
  const auto t0 = std::chrono::steady_clock::now();
  if (!point.allFinite() || !normal.allFinite() || !(normal.norm() > 0))
    throw InputError("HRBF drag refit: the moved sample needs a finite point and a non-zero normal");
  const int N = samples_.size();
  const Kernel& kernel = options_.kernel;
  const int m = monomialCount<Dim>(options_.polynomial);
  const Eigen::Index nR = Krr_.rows();
  const Eigen::Index blocksR = Eigen::Index(N - 1) * B;  // rows of R that are sample conditions

  // The border: conditions at every other sample against the moved centre, then the polynomial
  // orthogonality rows (the moved sample's polynomial values and gradients).
  Border Kri(nR, B);
  for (int i = 0, r = 0; i < N; ++i) {
    if (i == moved_) continue;
    Kri.template middleRows<B>(Eigen::Index(r) * B) = hrbfBlock<Dim>(kernel, samples_.points.col(i) - point);
    ++r;
  }
  if (m > 0) Kri.bottomRows(m) = hrbfPolynomialRows<Dim>(options_.polynomial, point).transpose();
  Block Kii = hrbfBlock<Dim>(kernel, Vec<Dim>::Zero());
  Kii.diagonal().array() += kernel.smoothingSign() * options_.smoothing;
  const Vec<Dim> unitNormal = normal.normalized();
  Eigen::Matrix<double, B, 1> bI;
  bI << 0.0, unitNormal;
  if (!Kri.allFinite() || !Kii.allFinite())
    throw NumericalError("the system has non-finite entries (kernel values overflow for this radius?)");
  const double assemblyMs = msSince(t0);

  // Schur complement of K_RR.
  Eigen::MatrixXd Ydyn = Kri;
  lu_->solveInPlace(Ydyn);
  const Border Y = Ydyn;
  const Block S = Kii - Kri.transpose() * Y;
  const Eigen::PartialPivLU<Block> schur(S);
  const double schurRcond = schur.rcond();
  if (!(schurRcond > 1e-15))
    throw NumericalError("singular system: the moved sample adds no independent conditions (Schur complement rcond " +
                         shortNumber(schurRcond) + ")");

  // x = K⁻¹ b, with z = K_RR⁻¹ b_R from the factorisation.
  Eigen::Matrix<double, B, 1> xI = schur.solve((bI - Kri.transpose() * zR_).eval());
  Eigen::VectorXd xR = zR_ - Y * xI;

  // One step of iterative refinement on the whole system, then the residual check.
  auto residual = [&](Eigen::VectorXd& rR, Eigen::Matrix<double, B, 1>& rI) {
    rR = bR_ - Krr_ * xR - Kri * xI;
    rI = bI - Kri.transpose() * xR - Kii * xI;
  };
  Eigen::VectorXd rR;
  Eigen::Matrix<double, B, 1> rI;
  residual(rR, rI);
  solveBordered(Kri, schur, Y, rR, rI);
  xR += rR;
  xI += rI;
  residual(rR, rI);
  // K is symmetric: its row sums are its column sums.
  const double normInfK = std::max((krrColumnSums_ + Kri.cwiseAbs().rowwise().sum()).maxCoeff(),
                                   (Kri.cwiseAbs().colwise().sum().transpose() + Kii.cwiseAbs().rowwise().sum()).maxCoeff());
  const double xNorm = std::max(xR.cwiseAbs().maxCoeff(), xI.cwiseAbs().maxCoeff());
  const double bNorm = std::max(bR_.cwiseAbs().maxCoeff(), bI.cwiseAbs().maxCoeff());
  const double rNorm = std::max(rR.cwiseAbs().maxCoeff(), rI.cwiseAbs().maxCoeff());
  if (!xR.allFinite() || !xI.allFinite() || !(rNorm <= kResidualTolerance * (normInfK * xNorm + bNorm)))
    throw NumericalError("the bordered drag solve is not accurate (relative residual " +
                         shortNumber(rNorm / (normInfK * xNorm + bNorm)) + ")");

  // 1-norm condition estimate of the whole K (symmetric: its 1- and ∞-norms agree).
  const double inverseNorm = symmetricInverseNormEstimate(nR + B, [&](Eigen::VectorXd& v) {
    Eigen::VectorXd vR = v.head(nR);
    Eigen::Matrix<double, B, 1> vI = v.tail<B>();
    solveBordered(Kri, schur, Y, vR, vI);
    v.head(nR) = vR;
    v.tail<B>() = vI;
  });
  const double condition = normInfK * inverseNorm;

  // Back to fitHrbf's layout: centres in the samples' order, the moved one in its place.
  Points<Dim> centres = samples_.points;
  centres.col(moved_) = point;
  Eigen::VectorXd alpha(N);
  Points<Dim> beta(Dim, N);
  for (int i = 0, r = 0; i < N; ++i) {
    const Eigen::Matrix<double, B, 1> x =
        i == moved_ ? xI : Eigen::Matrix<double, B, 1>(xR.template segment<B>(Eigen::Index(r++) * B));
    alpha(i) = x(0);
    beta.col(i) = x.template tail<Dim>();
  }
  Eigen::VectorXd poly = xR.segment(blocksR, m);

  if (report) {
    report->nSamples = N;
    report->nUnknowns = int(N * B + m);
    report->solver = "bordered-lu";
    report->conditionEstimate = condition;
    report->warnings = polynomialOrderWarnings(kernel, options_.polynomial);
    if (auto warning = illConditionedWarning(condition, report->solver)) report->warnings.push_back(*warning);
    report->assemblyMs = assemblyMs;
    report->fitMs = msSince(t0);
    report->solveMs = report->fitMs - assemblyMs;
  }
  return HrbfModel<Dim>(kernel, options_.polynomial, std::move(centres), std::move(alpha), std::move(beta),
                        std::move(poly));
}

template class HrbfBorderedRefit<2>;
template class HrbfBorderedRefit<3>;

}  // namespace hermite
