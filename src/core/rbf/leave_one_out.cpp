#include "core/rbf/leave_one_out.h"

#include <Eigen/LU>
#include <cmath>

#include "core/base/errors.h"
#include "core/base/memory_check.h"
#include "core/rbf/dense_fit_memory.h"

namespace hermite {

namespace {

// Fills the statistics from the per-sample errors.
void summarise(LeaveOneOutResult& r, double spacing) {
  const double n = double(r.valueError.size());
  double sv = 0, sg = 0;
  for (std::size_t i = 0; i < r.valueError.size(); ++i) {
    sv += r.valueError[i] * r.valueError[i];
    sg += r.gradientError[i] * r.gradientError[i];
    r.maxValue = std::max(r.maxValue, r.valueError[i]);
    r.maxGradient = std::max(r.maxGradient, r.gradientError[i]);
  }
  r.rmsValue = std::sqrt(sv / n);
  r.rmsGradient = std::sqrt(sg / n);
  r.combined = std::hypot(r.rmsValue, spacing * r.rmsGradient);
}

template <int Dim>
void requireTwo(const HermiteSamples<Dim>& samples) {
  if (samples.points.cols() < 2) throw InputError("leave-one-out: needs at least two samples");
}

}  // namespace

template <int Dim>
LeaveOneOutResult hrbfLeaveOneOut(const HermiteSamples<Dim>& samples, const HrbfOptions& options) {
  requireTwo(samples);
  constexpr int B = Dim + 1;
  // Peak: the kernel block, the saddle matrix, its LU and its inverse (4 square matrices).
  const std::uint64_t unknowns = std::uint64_t(samples.size()) * B + monomialCount<Dim>(options.polynomial);
  checkMemory({saturatingProduct({4, unknowns, unknowns, sizeof(double)}),
               "leave-one-out of " + std::to_string(unknowns) + " unknowns (4 matrices of that size squared)"},
              kDenseFitRemedy);
  const SaddleSystem sys = assembleHrbf(samples, options);
  const Eigen::Index n = sys.A.rows(), m = sys.P.cols();
  // The whole symmetric saddle matrix (assembleHrbf fills A's lower triangle only).
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(n + m, n + m);
  M.topLeftCorner(n, n) = sys.A.template selfadjointView<Eigen::Lower>();
  M.topRightCorner(n, m) = sys.P;
  M.bottomLeftCorner(m, n) = sys.P.transpose();
  Eigen::VectorXd y = Eigen::VectorXd::Zero(n + m);
  y.head(n) = sys.b;

  const Eigen::FullPivLU<Eigen::MatrixXd> lu(M);
  if (!lu.isInvertible())
    throw NumericalError("leave-one-out: the fit's system is singular (rank " + std::to_string(lu.rank()) + " of " +
                         std::to_string(n + m) + ")");
  const Eigen::MatrixXd Minv = lu.inverse();
  const Eigen::VectorXd z = Minv * y;

  const int N = int(samples.points.cols());
  LeaveOneOutResult r;
  r.valueError.resize(N);
  r.gradientError.resize(N);
  for (int i = 0; i < N; ++i) {
    const Eigen::Index s = Eigen::Index(i) * B;
    const Mat<B> block = Minv.template block<B, B>(s, s);
    const Eigen::FullPivLU<Mat<B>> blu(block);
    if (!blu.isInvertible())
      throw NumericalError("leave-one-out: without sample " + std::to_string(i) +
                           " the system is singular (too few samples left for the polynomial term)");
    // y_S − pred_S: the prediction's value error is its first entry (yᵢ = 0), the gradient
    // error the rest (the rows are f(pᵢ) and ∇f(pᵢ) with right-hand side 0 and nᵢ).
    const Vec<B> e = blu.solve(Vec<B>(z.template segment<B>(s)));
    r.valueError[i] = std::abs(e(0));
    r.gradientError[i] = e.template tail<Dim>().norm();
  }
  summarise(r, meanSampleSpacing<Dim>(samples.points));
  return r;
}

template <int Dim>
LeaveOneOutResult hrbfLeaveOneOutBruteForce(const HermiteSamples<Dim>& samples, const HrbfOptions& options) {
  requireTwo(samples);
  const int N = int(samples.points.cols());
  LeaveOneOutResult r;
  r.valueError.resize(N);
  r.gradientError.resize(N);
  for (int i = 0; i < N; ++i) {
    const HermiteSamples<Dim> rest = withoutSample(samples, i);
    const HrbfModel<Dim> model = fitHrbf(rest, options);
    Vec<Dim> g;
    r.valueError[i] = std::abs(model.evaluate(samples.points.col(i), &g));
    r.gradientError[i] = (g - samples.normals.col(i)).norm();
  }
  summarise(r, meanSampleSpacing<Dim>(samples.points));
  return r;
}

template LeaveOneOutResult hrbfLeaveOneOut<2>(const HermiteSamples<2>&, const HrbfOptions&);
template LeaveOneOutResult hrbfLeaveOneOut<3>(const HermiteSamples<3>&, const HrbfOptions&);
template LeaveOneOutResult hrbfLeaveOneOutBruteForce<2>(const HermiteSamples<2>&, const HrbfOptions&);
template LeaveOneOutResult hrbfLeaveOneOutBruteForce<3>(const HermiteSamples<3>&, const HrbfOptions&);

}  // namespace hermite
