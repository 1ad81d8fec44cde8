#pragma once
// Hermite RBF implicit (docs/maths.md, HRBF system):
//   f(x) = Σⱼ αⱼ φ(‖x − cⱼ‖) − βⱼ·∇φ(x − cⱼ) + p(x),   cⱼ = pⱼ,
// with f(pᵢ) = 0, ∇f(pᵢ) = nᵢ and Σⱼ αⱼ q(pⱼ) + βⱼ·∇q(pⱼ) = 0 for every monomial q.

#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "core/points/hermite_samples.h"
#include "core/rbf/dense_solver.h"
#include "core/rbf/kernels.h"
#include "core/rbf/polynomial.h"
#include "core/rbf/radial_sum.h"

namespace hermite {

// Largest accepted smoothing λ. Beyond about 1e154 the solver's products of the kernel block
// overflow; from far below this bound on the fit is already the polynomial least-squares fit
// (α, β ≈ b/λ), so nothing is lost by refusing larger values.
inline constexpr double kMaxSmoothing = 1e100;

struct HrbfOptions {
  Kernel kernel{KernelType::Cubic, 1.0};
  Polynomial polynomial = Polynomial::Linear;  // linear: enough for every kernel but polyharmonic
  double smoothing = 0.0;                      // λ in [0, kMaxSmoothing]; 0 = interpolation
  SolverChoice solver = SolverChoice::Auto;    // auto: cheapest path the kernel allows
  // Polled during assembly and by the factorisation (SaddleSystem::cancel): the fit throws
  // Cancelled once it is set. Null: never cancelled. Not owned.
  const CancelToken* cancel = nullptr;
};

// What a fit reports besides the model (the `fit --json` keys come from here).
struct FitReport {
  int nSamples = 0;
  int nUnknowns = 0;
  std::string solver;
  double conditionEstimate = 0;
  double fitMs = 0;       // assembly + factorisation + solve, wall clock
  double assemblyMs = 0;  // building the kernel and polynomial blocks
  double solveMs = 0;     // factorisation + solve (solveSaddle)
  double factorMs = 0;    // the factorisation alone (its last attempt when one fell back)
  double factorGflops = 0;  // its floating-point operations per second, 10⁹
  // solveMs by phase in the order they ran (prepare, qr, project, factor, condition, solve), ms;
  // a phase that ran twice (a fallback) appears twice.
  std::vector<std::pair<std::string, double>> solvePhasesMs;
  std::vector<std::string> warnings;
};

template <int Dim>
class HrbfModel : public RadialSum<Dim> {
 public:
  HrbfModel() = default;
  HrbfModel(Kernel kernel, Polynomial polynomial, Points<Dim> centres, Eigen::VectorXd alpha,
            Points<Dim> beta, Eigen::VectorXd poly, Vec<Dim> polyOrigin = Vec<Dim>::Zero())
      : RadialSum<Dim>(kernel, polynomial, std::move(centres), std::move(alpha), std::move(beta),
                       std::move(poly), polyOrigin) {}
};

// The saddle system of the fit (kernel block with smoothing, polynomial block, right-hand side),
// unknowns ordered per centre as [αⱼ, βⱼ]; for tests, diagnostics and the r explorer.
template <int Dim>
SaddleSystem assembleHrbf(const HermiteSamples<Dim>& samples, const HrbfOptions& options);

// The (Dim+1)² block of the HRBF system coupling the conditions at pᵢ (f, then ∇f) with the
// unknowns of centre pⱼ (α, then β), d = pᵢ − pⱼ (kernels.h: a = φ′/x, e = a′/x):
//   [ φ      −a dᵀ        ]
//   [ a d    −(aI + e ddᵀ) ]        symmetric overall: block (j, i) is the transpose
template <int Dim>
Eigen::Matrix<double, Dim + 1, Dim + 1> hrbfBlock(const Kernel& kernel, const Vec<Dim>& d);

// The Dim + 1 rows of the polynomial block P for the conditions at p: monomial values, then
// their gradients (Dim + 1 × monomialCount), on the stack.
template <int Dim>
using HrbfPolynomialRows = Eigen::Matrix<double, Dim + 1, Eigen::Dynamic, 0, Dim + 1, kMaxMonomials<Dim>>;
template <int Dim>
HrbfPolynomialRows<Dim> hrbfPolynomialRows(Polynomial polynomial, const Vec<Dim>& p);

// Fits the HRBF to validated samples. Throws NumericalError when no solver path succeeds or the
// coefficients are not finite; warnings (order, conditioning, fallback) go to the report.
// The polynomial part is written about exactCentre(samples.points) (docs/maths.md, Centring).
template <int Dim>
HrbfModel<Dim> fitHrbf(const HermiteSamples<Dim>& samples, const HrbfOptions& options,
                       FitReport* report = nullptr);
// fitHrbf with the polynomial about a given origin, whose subtraction from every sample must be
// exact (a zero origin: the polynomial in the samples' own coordinates, as the partition of
// unity's local fits in their box frame).
template <int Dim>
HrbfModel<Dim> fitHrbfAbout(const HermiteSamples<Dim>& samples, const HrbfOptions& options, const Vec<Dim>& origin,
                            FitReport* report = nullptr);

// The part every fit method shares: solves the assembled system, collects the warnings
// (polynomial order, solver) and fills `report` (may be null); `start` is when assembly began.
SaddleSolution solveFitSystem(SaddleSystem system, SolverChoice solver, const Kernel& kernel, Polynomial polynomial,
                              int nSamples, std::chrono::steady_clock::time_point start, FitReport* report);

// Warnings every fit shares: polynomial below the kernel's order (docs/maths.md, Kernels).
std::vector<std::string> polynomialOrderWarnings(const Kernel& kernel, Polynomial polynomial);

// Definiteness of the kernel block on null(Pᵀ) for the solver, or 0 when unknown
// (polynomial below the order, or smoothing with the wrong sign).
int kernelDefiniteSign(const Kernel& kernel, Polynomial polynomial, double smoothing);

// The lowest polynomial the kernel's conditional definiteness needs (linear for orders 1 and 2,
// quadratic for 3), or None for a positive definite kernel.
Polynomial definitenessPolynomial(const Kernel& kernel);

}  // namespace hermite
