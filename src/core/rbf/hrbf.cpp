#include "core/rbf/hrbf.h"

#include <chrono>
#include <functional>
#include <string>

#include "core/base/errors.h"
#include "core/base/exact_centre.h"
#include "core/base/ms_since.h"
#include "core/rbf/dense_fit_memory.h"
#include "core/rbf/kept_kernel_matrix.h"

namespace hermite {

std::vector<std::string> polynomialOrderWarnings(const Kernel& kernel, Polynomial polynomial) {
  std::vector<std::string> w;
  const int order = kernel.cpdOrder();
  if (polynomialDegree(polynomial) < order - 1) {
    w.push_back("polynomial '" + std::string(polynomialName(polynomial)) + "' is below the order of kernel '" +
                std::string(kernelName(kernel.type)) + "' (conditionally definite of order " +
                std::to_string(order) + ": needs degree ≥ " + std::to_string(order - 1) +
                "); the system is not guaranteed to be solvable");
  }
  return w;
}

int kernelDefiniteSign(const Kernel& kernel, Polynomial polynomial, double smoothing) {
  if (smoothing < 0) return 0;
  if (polynomialDegree(polynomial) < kernel.cpdOrder() - 1) return 0;
  return kernel.smoothingSign() > 0 ? 1 : -1;
}

Polynomial definitenessPolynomial(const Kernel& kernel) {
  const int order = kernel.cpdOrder();
  if (order == 0) return Polynomial::None;
  return order <= 2 ? Polynomial::Linear : order == 3 ? Polynomial::Quadratic : Polynomial::None;
}

SaddleSolution solveFitSystem(SaddleSystem system, SolverChoice solver, const Kernel& kernel, Polynomial polynomial,
                              int nSamples, std::chrono::steady_clock::time_point start, FitReport* report) {
  const Eigen::Index nUnknowns = system.A.rows() + system.P.cols();
  std::vector<std::string> warnings = polynomialOrderWarnings(kernel, polynomial);
  const auto tSolve = std::chrono::steady_clock::now();
  SaddleSolution sol = solveSaddle(std::move(system), solver);
  warnings.insert(warnings.end(), sol.warnings.begin(), sol.warnings.end());
  if (report) {
    report->nSamples = nSamples;
    report->nUnknowns = static_cast<int>(nUnknowns);
    report->solver = sol.solver;
    report->conditionEstimate = sol.conditionEstimate;
    report->warnings = std::move(warnings);
    report->assemblyMs = std::chrono::duration<double, std::milli>(tSolve - start).count();
    report->solveMs = msSince(tSolve);
    report->fitMs = msSince(start);
    report->factorMs = factorMs(sol);
    report->factorGflops = report->factorMs > 0 ? sol.factorFlops / (report->factorMs * 1e6) : 0.0;
    report->solvePhasesMs = sol.phaseMs;
  }
  return sol;
}

namespace {

// Writes the kernel block's lower triangle and diagonal into A (n × n, n = (Dim + 1)·N), block by
// block (row block i = conditions at pᵢ, column block j = centre pⱼ: hrbfBlock), with the
// smoothing `lambda` on the diagonal. The strict upper triangle is neither read nor written:
// writing the transposed blocks here would stride across columns (slower), and the Cholesky
// paths never need it (SaddleSystem::assembleLower). Polls `cancel` per column block (a few
// microseconds of work each) and throws Cancelled after the loop when it was set.
template <int Dim>
void assembleKernelLower(const Kernel& kernel, const Points<Dim>& p, double lambda, Eigen::MatrixXd& A,
                         const CancelToken* cancel) {
  constexpr int B = Dim + 1;
  const int N = int(p.cols());
#pragma omp parallel for schedule(dynamic, 8)
  for (int j = 0; j < N; ++j) {
    if (cancel && cancel->cancelled()) continue;  // an exception cannot leave the parallel loop
    for (int i = j; i < N; ++i)
      A.template block<B, B>(Eigen::Index(i) * B, Eigen::Index(j) * B) = hrbfBlock<Dim>(kernel, p.col(i) - p.col(j));
  }
  throwIfCancelled(cancel);
  if (lambda != 0) A.diagonal().array() += lambda;
}

// assembleKernelLower for these points and options, as SaddleSystem::assembleLower.
template <int Dim>
std::function<void(Eigen::MatrixXd&)> kernelBlockAssembler(const Points<Dim>& p, const HrbfOptions& options) {
  const double lambda = options.kernel.smoothingSign() * options.smoothing;
  return [kernel = options.kernel, points = p, lambda, cancel = options.cancel](Eigen::MatrixXd& A) {
    assembleKernelLower<Dim>(kernel, points, lambda, A, cancel);
  };
}

}  // namespace

template <int Dim>
SaddleSystem assembleHrbf(const HermiteSamples<Dim>& samples, const HrbfOptions& options) {
  const int N = samples.size();
  if (N < 1) throw InputError("HRBF fit: no samples");
  if (!(options.smoothing >= 0)) throw InputError("HRBF fit: smoothing must be ≥ 0");
  if (!(options.smoothing <= kMaxSmoothing)) throw InputError("HRBF fit: smoothing must be ≤ 1e100");
  const Kernel& kernel = options.kernel;
  if (kernel.usesRadius() && !(kernel.radius > 0)) throw InputError("HRBF fit: radius must be > 0");
  constexpr int B = Dim + 1;  // unknowns per centre: α, β (Dim); rows per sample: f, ∇f (Dim)
  const int m = monomialCount<Dim>(options.polynomial);
  const Eigen::Index n = Eigen::Index(N) * B;

  SaddleSystem sys;
  sys.A = takeKernelMatrix(n);  // every entry the solver reads is written below
  sys.P.resize(n, m);
  sys.b.setZero(n);
  sys.definiteSign = kernelDefiniteSign(kernel, options.polynomial, options.smoothing);
  const double lambda = kernel.smoothingSign() * options.smoothing;
  const Points<Dim>& p = samples.points;

  assembleKernelLower<Dim>(kernel, p, lambda, sys.A, options.cancel);
  for (int i = 0; i < N; ++i) {
    sys.b.template segment<Dim>(Eigen::Index(i) * B + 1) = samples.normals.col(i);
    if (m > 0) sys.P.middleRows(Eigen::Index(i) * B, B) = hrbfPolynomialRows<Dim>(options.polynomial, p.col(i));
  }
  // No polynomial for a conditionally definite kernel: A is still definite on the complement of
  // the polynomial it needs, which the projected-cholesky path uses (dense_solver.h).
  const Polynomial needed = definitenessPolynomial(kernel);
  if (m == 0 && sys.definiteSign == 0 && needed != Polynomial::None) {
    sys.definiteOnSign = kernelDefiniteSign(kernel, needed, options.smoothing);
    sys.definiteOn.resize(n, monomialCount<Dim>(needed));
    for (int i = 0; i < N; ++i) sys.definiteOn.middleRows(Eigen::Index(i) * B, B) = hrbfPolynomialRows<Dim>(needed, p.col(i));
  }
  return sys;
}

template <int Dim>
Eigen::Matrix<double, Dim + 1, Dim + 1> hrbfBlock(const Kernel& kernel, const Vec<Dim>& d) {
  const RadialTerms t = kernel.terms(d.norm());
  Eigen::Matrix<double, Dim + 1, Dim + 1> blk;
  blk(0, 0) = t.phi;
  blk.template block<1, Dim>(0, 1) = -t.a * d.transpose();
  blk.template block<Dim, 1>(1, 0) = t.a * d;
  blk.template block<Dim, Dim>(1, 1) = -(t.a * Mat<Dim>::Identity() + t.e * d * d.transpose());
  return blk;
}

template <int Dim>
HrbfPolynomialRows<Dim> hrbfPolynomialRows(Polynomial polynomial, const Vec<Dim>& p) {
  const int m = monomialCount<Dim>(polynomial);
  HrbfPolynomialRows<Dim> rows(Dim + 1, m);
  if (m == 0) return rows;
  Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxMonomials<Dim>, 1> q(m);
  Eigen::Matrix<double, Dim, Eigen::Dynamic, 0, Dim, kMaxMonomials<Dim>> gq(Dim, m);
  monomials<Dim>(polynomial, p, q, gq);
  rows.row(0) = q.transpose();
  rows.bottomRows(Dim) = gq;
  return rows;
}

template <int Dim>
HrbfModel<Dim> fitHrbf(const HermiteSamples<Dim>& samples, const HrbfOptions& options, FitReport* report) {
  const Vec<Dim> origin =
      options.polynomial != Polynomial::None ? exactCentre<Dim>(samples.points) : Vec<Dim>::Zero();
  return fitHrbfAbout<Dim>(samples, options, origin, report);
}

template <int Dim>
HrbfModel<Dim> fitHrbfAbout(const HermiteSamples<Dim>& samples, const HrbfOptions& options, const Vec<Dim>& origin,
                            FitReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  const int m = monomialCount<Dim>(options.polynomial);
  const int sign = kernelDefiniteSign(options.kernel, options.polynomial, options.smoothing);
  const bool projectable = m == 0 && definitenessPolynomial(options.kernel) != Polynomial::None;
  const std::int64_t unknowns = std::int64_t(samples.size()) * (Dim + 1) + m;
  const SolverChoice path = plannedSolverPath(options.solver, m, sign, projectable);
  try {
    checkDenseFitMemory(unknowns, path, m);
  } catch (const MemoryLimitError&) {
    if (releaseKeptKernelMatrix() == 0) throw;  // the kept matrix's memory may make the difference
    checkDenseFitMemory(unknowns, path, m);
  }
  // The polynomial part about `origin` (docs/maths.md, Centring): P is built from the centred
  // points, the kernel block is unchanged (it sees only exact differences pᵢ − pⱼ).
  throwIfCancelled(options.cancel);
  HermiteSamples<Dim> centred;
  const HermiteSamples<Dim>* fitted = &samples;
  if (!origin.isZero()) {
    centred = samples;
    centred.points.colwise() -= origin;
    fitted = &centred;
  }
  SaddleSystem sys = assembleHrbf(*fitted, options);
  // The system goes to the solver unchanged, so the Cholesky paths may rebuild it instead of
  // keeping a copy in A's upper triangle.
  sys.assembleLower = kernelBlockAssembler<Dim>(fitted->points, options);
  sys.cancel = options.cancel;
  sys.keepMatrix = true;
  const Kernel& kernel = options.kernel;
  constexpr int B = Dim + 1;
  const int N = samples.size();
  const Points<Dim>& p = samples.points;
  SaddleSolution sol =
      solveFitSystem(std::move(sys), options.solver, kernel, options.polynomial, N, t0, report);

  Eigen::VectorXd alpha(N);
  Points<Dim> beta(Dim, N);
  for (int j = 0; j < N; ++j) {
    alpha(j) = sol.x(Eigen::Index(j) * B);
    beta.col(j) = sol.x.template segment<Dim>(Eigen::Index(j) * B + 1);
  }
  HrbfModel<Dim> model(kernel, options.polynomial, p, std::move(alpha), std::move(beta), std::move(sol.c), origin);
  return model;
}

template Eigen::Matrix<double, 3, 3> hrbfBlock<2>(const Kernel&, const Vec<2>&);
template Eigen::Matrix<double, 4, 4> hrbfBlock<3>(const Kernel&, const Vec<3>&);
template HrbfPolynomialRows<2> hrbfPolynomialRows<2>(Polynomial, const Vec<2>&);
template HrbfPolynomialRows<3> hrbfPolynomialRows<3>(Polynomial, const Vec<3>&);
template SaddleSystem assembleHrbf<2>(const HermiteSamples<2>&, const HrbfOptions&);
template SaddleSystem assembleHrbf<3>(const HermiteSamples<3>&, const HrbfOptions&);
template HrbfModel<2> fitHrbf<2>(const HermiteSamples<2>&, const HrbfOptions&, FitReport*);
template HrbfModel<3> fitHrbf<3>(const HermiteSamples<3>&, const HrbfOptions&, FitReport*);
template HrbfModel<2> fitHrbfAbout<2>(const HermiteSamples<2>&, const HrbfOptions&, const Vec<2>&, FitReport*);
template HrbfModel<3> fitHrbfAbout<3>(const HermiteSamples<3>&, const HrbfOptions&, const Vec<3>&, FitReport*);

}  // namespace hermite
