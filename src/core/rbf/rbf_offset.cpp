#include "core/rbf/rbf_offset.h"

#include <chrono>

#include "core/base/errors.h"
#include "core/base/exact_centre.h"
#include "core/rbf/dense_fit_memory.h"
#include "core/base/huge_pages.h"

namespace hermite {

template <int Dim>
RbfOffsetModel<Dim> fitRbfOffset(const HermiteSamples<Dim>& samples, const RbfOffsetOptions& options,
                                 FitReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  const int N = samples.size();
  if (N < 1) throw InputError("RBF-offset fit: no samples");
  if (!(options.shift > 0)) throw InputError("RBF-offset fit: shift must be > 0");
  if (!(options.smoothing >= 0)) throw InputError("RBF-offset fit: smoothing must be ≥ 0");
  if (!(options.smoothing <= kMaxSmoothing)) throw InputError("RBF-offset fit: smoothing must be ≤ 1e100");
  const Kernel& kernel = options.kernel;
  const double delta = options.shift;

  // Centres per sample i: pᵢ, pᵢ + δnᵢ, pᵢ − δnᵢ with values 0, +δ, −δ.
  const Eigen::Index n = Eigen::Index(N) * 3;
  Points<Dim> centres(Dim, n);
  throwIfCancelled(options.cancel);
  SaddleSystem sys;
  sys.cancel = options.cancel;
  sys.b.resize(n);
  for (int i = 0; i < N; ++i) {
    centres.col(3 * i) = samples.points.col(i);
    centres.col(3 * i + 1) = samples.points.col(i) + delta * samples.normals.col(i);
    centres.col(3 * i + 2) = samples.points.col(i) - delta * samples.normals.col(i);
    sys.b.template segment<3>(3 * i) << 0.0, delta, -delta;
  }
  const int m = monomialCount<Dim>(options.polynomial);
  sys.definiteSign = kernelDefiniteSign(kernel, options.polynomial, options.smoothing);
  checkDenseFitMemory(n + m, plannedSolverPath(options.solver, m, sys.definiteSign), m);
  sys.A.resize(n, n);
  adviseHugePages(sys.A.data(), sizeof(double) * std::size_t(n) * std::size_t(n));
  sys.P.resize(n, m);
#pragma omp parallel for schedule(dynamic, 16)
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = j; i < n; ++i) sys.A(i, j) = kernel.phi((centres.col(i) - centres.col(j)).norm());
  if (options.smoothing != 0) sys.A.diagonal().array() += kernel.smoothingSign() * options.smoothing;
  // The polynomial about an exact centre (zero for data near the origin): docs/maths.md, Centring.
  const Vec<Dim> origin = m > 0 ? exactCentre<Dim>(centres) : Vec<Dim>::Zero();
  if (m > 0) {
    Eigen::VectorXd q(m);
    Eigen::Matrix<double, Dim, Eigen::Dynamic> gq(Dim, m);
    for (Eigen::Index i = 0; i < n; ++i) {
      monomials<Dim>(options.polynomial, centres.col(i) - origin, q, gq);
      sys.P.row(i) = q.transpose();
    }
  }

  SaddleSolution sol = solveFitSystem(std::move(sys), options.solver, kernel, options.polynomial, N, t0, report);
  return RbfOffsetModel<Dim>(kernel, options.polynomial, std::move(centres), std::move(sol.x), std::move(sol.c), delta,
                             origin);
}

template RbfOffsetModel<2> fitRbfOffset<2>(const HermiteSamples<2>&, const RbfOffsetOptions&, FitReport*);
template RbfOffsetModel<3> fitRbfOffset<3>(const HermiteSamples<3>&, const RbfOffsetOptions&, FitReport*);

}  // namespace hermite
