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
typename HrbfBorderedRefit<Dim>::Bordered HrbfBorderedRefit<Dim>::assembleBorder(const Vec<Dim>& point) const {
  const int N = samples_.size();
  const Kernel& kernel = options_.kernel;
  const int m = monomialCount<Dim>(options_.polynomial);
  // The border: conditions at every other sample against the moved centre, then the polynomial
  // orthogonality rows (the moved sample's polynomial values and gradients).
  Bordered k;
  k.Kri.resize(Krr_.rows(), B);
  for (int i = 0, r = 0; i < N; ++i) {
    if (i == moved_) continue;
    k.Kri.template middleRows<B>(Eigen::Index(r) * B) = hrbfBlock<Dim>(kernel, samples_.points.col(i) - point);
    ++r;
  }
  if (m > 0) k.Kri.bottomRows(m) = hrbfPolynomialRows<Dim>(options_.polynomial, point).transpose();
  k.Kii = hrbfBlock<Dim>(kernel, Vec<Dim>::Zero());
  k.Kii.diagonal().array() += kernel.smoothingSign() * options_.smoothing;
  if (!k.Kri.allFinite() || !k.Kii.allFinite())
    throw NumericalError("the system has non-finite entries (kernel values overflow for this radius?)");
  return k;
}

template <int Dim>
void HrbfBorderedRefit<Dim>::factorBorder(Bordered& k) const {
  Eigen::MatrixXd Ydyn = k.Kri;
  lu_->solveInPlace(Ydyn);
  k.Y = Ydyn;
  k.schur.compute(Block(k.Kii - k.Kri.transpose() * k.Y));
  const double schurRcond = k.schur.rcond();
  if (!(schurRcond > 1e-15))
    throw NumericalError("singular system: the moved sample adds no independent conditions (Schur complement rcond " +
                         shortNumber(schurRcond) + ")");
}

template <int Dim>
void HrbfBorderedRefit<Dim>::solveBordered(const Bordered& k, Eigen::VectorXd& rhsR, BVec& rhsI) const {
  lu_->solveInPlace(rhsR);                                        // y = K_RR⁻¹ r_R
  rhsI = k.schur.solve((rhsI - k.Kri.transpose() * rhsR).eval());  // x_I = S⁻¹ (r_I − K_IR y)
  rhsR -= k.Y * rhsI;                                              // x_R = y − Y x_I
}

template <int Dim>
double HrbfBorderedRefit<Dim>::refineAndCheck(const Bordered& k, const BVec& bI, Eigen::VectorXd& xR, BVec& xI) const {
  auto residual = [&](Eigen::VectorXd& rR, BVec& rI) {
    rR = bR_ - Krr_ * xR - k.Kri * xI;
    rI = bI - k.Kri.transpose() * xR - k.Kii * xI;
  };
  Eigen::VectorXd rR;
  BVec rI;
  residual(rR, rI);
  solveBordered(k, rR, rI);
  xR += rR;
  xI += rI;
  residual(rR, rI);
  // K is symmetric: its row sums are its column sums.
  const double normInfK =
      std::max((krrColumnSums_ + k.Kri.cwiseAbs().rowwise().sum()).maxCoeff(),
               (k.Kri.cwiseAbs().colwise().sum().transpose() + k.Kii.cwiseAbs().rowwise().sum()).maxCoeff());
  const double xNorm = std::max(xR.cwiseAbs().maxCoeff(), xI.cwiseAbs().maxCoeff());
  const double bNorm = std::max(bR_.cwiseAbs().maxCoeff(), bI.cwiseAbs().maxCoeff());
  const double rNorm = std::max(rR.cwiseAbs().maxCoeff(), rI.cwiseAbs().maxCoeff());
  if (!xR.allFinite() || !xI.allFinite() || !(rNorm <= kResidualTolerance * (normInfK * xNorm + bNorm)))
    throw NumericalError("the bordered drag solve is not accurate (relative residual " +
                         shortNumber(rNorm / (normInfK * xNorm + bNorm)) + ")");
  return normInfK;
}

template <int Dim>
HrbfModel<Dim> HrbfBorderedRefit<Dim>::model(const Vec<Dim>& point, const Eigen::VectorXd& xR, const BVec& xI) const {
  const int N = samples_.size();
  Points<Dim> centres = samples_.points;
  centres.col(moved_) = point;
  Eigen::VectorXd alpha(N);
  Points<Dim> beta(Dim, N);
  for (int i = 0, r = 0; i < N; ++i) {
    const BVec x = i == moved_ ? xI : BVec(xR.template segment<B>(Eigen::Index(r++) * B));
    alpha(i) = x(0);
    beta.col(i) = x.template tail<Dim>();
  }
  Eigen::VectorXd poly = xR.segment(Eigen::Index(N - 1) * B, monomialCount<Dim>(options_.polynomial));
  return HrbfModel<Dim>(options_.kernel, options_.polynomial, std::move(centres), std::move(alpha), std::move(beta),
                        std::move(poly));
}

template <int Dim>
HrbfModel<Dim> HrbfBorderedRefit<Dim>::fit(const Vec<Dim>& point, const Vec<Dim>& normal, FitReport* report) const {
  const auto t0 = std::chrono::steady_clock::now();
  if (!point.allFinite() || !normal.allFinite() || !(normal.norm() > 0))
    throw InputError("HRBF drag refit: the moved sample needs a finite point and a non-zero normal");
  Bordered k = assembleBorder(point);
  BVec bI;
  bI << 0.0, normal.normalized();
  const double assemblyMs = msSince(t0);
  factorBorder(k);

  // x = K⁻¹ b, with z = K_RR⁻¹ b_R from the factorisation, refined and checked.
  BVec xI = k.schur.solve((bI - k.Kri.transpose() * zR_).eval());
  Eigen::VectorXd xR = zR_ - k.Y * xI;
  const double normInfK = refineAndCheck(k, bI, xR, xI);

  // 1-norm condition estimate of the whole K (symmetric: its 1- and ∞-norms agree).
  const Eigen::Index nR = Krr_.rows();
  const double inverseNorm = symmetricInverseNormEstimate(nR + B, [&](Eigen::VectorXd& v) {
    Eigen::VectorXd vR = v.head(nR);
    BVec vI = v.tail<B>();
    solveBordered(k, vR, vI);
    v.head(nR) = vR;
    v.tail<B>() = vI;
  });
  const double condition = normInfK * inverseNorm;

  if (report) {
    const int N = samples_.size();
    report->nSamples = N;
    report->nUnknowns = int(N * B + monomialCount<Dim>(options_.polynomial));
    report->solver = "bordered-lu";
    report->conditionEstimate = condition;
    report->warnings = polynomialOrderWarnings(options_.kernel, options_.polynomial);
    if (auto warning = illConditionedWarning(condition, report->solver)) report->warnings.push_back(*warning);
    report->assemblyMs = assemblyMs;
    report->fitMs = msSince(t0);
    report->solveMs = report->fitMs - assemblyMs;
  }
  return model(point, xR, xI);
}

template class HrbfBorderedRefit<2>;
template class HrbfBorderedRefit<3>;

}  // namespace hermite
