#pragma once
// Dense symmetric saddle-point solves through LAPACKE (OpenBLAS), docs/maths.md, Solvers and conditioning:
//
//   [ A   P ] [x]   [b]      A: n × n symmetric (kernel block, smoothing already on its diagonal)
//   [ Pᵀ  0 ] [c] = [0]      P: n × m polynomial block (m may be 0)
//
// Paths:
//  - cholesky:            m = 0 and A positive definite (dpotrf)
//  - nullspace-cholesky:  m > 0, A definite on null(Pᵀ) with sign `definiteSign`: P = QR
//                         (dgeqrf), Zᵀ(±A)Z positive definite, dpotrf on it (n − m unknowns)
//  - ldlt:                Bunch–Kaufman symmetric-indefinite factorisation (dsytrf)
//  - lu:                  LU with partial pivoting (dgetrf)
//  - projected-cholesky:  m = 0, A definite only on null(Cᵀ) for a small block C (n × q: the
//                         polynomial the kernel's conditional definiteness needs, absent from
//                         the fit): C = QR, Cholesky of the trailing (n − q) block of QᵀAQ and a
//                         q × q Schur complement — the exact solution of A x = b at Cholesky cost
// Auto picks the cheapest path the kernel's definiteness allows, and LU rather than LDLᵀ for an
// indefinite system (OpenBLAS's dgetrf is faster than LAPACK's dsytrf, docs/performance.md); a
// failed factorisation falls back to LU with a warning. Only a failed LU or a non-finite result
// throws NumericalError.

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "core/base/cancel_token.h"
#include "core/base/enum_names.h"

namespace hermite {

enum class SolverChoice { Auto, Cholesky, NullspaceCholesky, Ldlt, Lu, ProjectedCholesky };
inline constexpr EnumName<SolverChoice> kSolverChoiceNames[] = {
    {"auto", SolverChoice::Auto},
    {"cholesky", SolverChoice::Cholesky},
    {"nullspace-cholesky", SolverChoice::NullspaceCholesky},
    {"ldlt", SolverChoice::Ldlt},
    {"lu", SolverChoice::Lu},
    {"projected-cholesky", SolverChoice::ProjectedCholesky}};

std::string_view solverName(SolverChoice s);
SolverChoice parseSolverChoice(std::string_view name);  // throws InputError

struct SaddleSystem {
  Eigen::MatrixXd A;  // n × n, symmetric; the lower triangle is read (solveSaddle mirrors it)
  // Rewrites A's lower triangle and diagonal as they were first assembled. Given, the Cholesky
  // paths never read or write A's strict upper triangle (no mirror, and half the pages of a
  // freshly allocated A stay untouched), and a failed Cholesky rebuilds A through it before it
  // falls back to LU. Empty: solveSaddle mirrors the lower triangle and keeps the upper as the copy.
  std::function<void(Eigen::MatrixXd&)> assembleLower;
  Eigen::MatrixXd P;  // n × m
  Eigen::VectorXd b;  // n
  // +1: A is positive definite on null(Pᵀ) (and on everything when m = 0); −1: negative
  // definite there; 0: no known definiteness (indefinite paths only).
  int definiteSign = 0;
  // m = 0 and definiteSign = 0 only: C (n × q) with A definite, of sign definiteOnSign, on
  // null(Cᵀ) — the Hermite rows of the polynomial a conditionally definite kernel needs. Empty:
  // unknown. Enables the projected-cholesky path.
  Eigen::MatrixXd definiteOn;
  int definiteOnSign = 0;
  // Polled between tiles of the factorisation (≤ 50 ms of work each): solveSaddle throws
  // Cancelled once it is set. Null: never cancelled.
  const CancelToken* cancel = nullptr;
  // True: after a successful solve, A's storage (with unspecified contents) is kept for the next
  // fit of the same size (kept_kernel_matrix.h) instead of freed. The HRBF fit sets it.
  bool keepMatrix = false;
};

struct SaddleSolution {
  Eigen::VectorXd x;  // n
  Eigen::VectorXd c;  // m
  std::string solver;              // the path that produced x: cholesky, nullspace-cholesky, ldlt, lu
  double conditionEstimate = 0;    // 1-norm estimate of the factorised matrix (LAPACK ?con)
  double factorFlops = 0;          // floating-point operations of the factorisation that produced x
  std::vector<std::string> warnings;
  // Wall-clock milliseconds of each phase ("prepare", "qr", "project", "factor", "condition",
  // "solve"), in order, for benchmarks and the diagnostics panel.
  std::vector<std::pair<std::string, double>> phaseMs;
};

// The path solveSaddle tries first for `choice` on a system with m polynomial terms and the
// kernel block's `definiteSign` (SaddleSystem::definiteSign): auto picks cholesky (m = 0) or
// nullspace-cholesky for a definite block; cholesky with m > 0 becomes nullspace-cholesky and
// nullspace-cholesky with m = 0 cholesky.
// With `projectable` (SaddleSystem::definiteOn given), auto picks projected-cholesky for an
// indefinite system; otherwise it picks lu there, and projected-cholesky falls back to lu.
SolverChoice plannedSolverPath(SolverChoice choice, Eigen::Index m, int definiteSign, bool projectable = false);

// Solves the system; A may be overwritten (it is taken by value where the caller moves it).
SaddleSolution solveSaddle(SaddleSystem system, SolverChoice choice = SolverChoice::Auto);

// Floating-point operations of factorising k unknowns by `path`: k³/3 for the Cholesky and LDLᵀ
// paths, 2k³/3 for LU (k is the size of the block the path factorises).
double factorisationFlops(SolverChoice path, Eigen::Index k);

// The milliseconds of the last "factor" phase, or 0.
double factorMs(const SaddleSolution& solution);

// Condition estimates above this get an "ill-conditioned" warning (about 4 of 16 digits left).
inline constexpr double kIllConditionedEstimate = 1e12;

// The one meaning of "condition estimate" in reports: 1/rcond, the reciprocal of a 1-norm
// reciprocal-condition estimate of the factorised matrix (LAPACK's ?con, or the same estimate
// made by Eigen or by the bordered refit). Above kIllConditionedEstimate: the one warning,
// naming the solver path; otherwise nothing.
std::optional<std::string> illConditionedWarning(double conditionEstimate, std::string_view solver);

// The whole saddle matrix K = [[A, P], [Pᵀ, 0]], both triangles, from a system whose A holds
// (at least) its lower triangle. Throws NumericalError on non-finite entries.
Eigen::MatrixXd saddleMatrix(const SaddleSystem& system);

// LU with partial pivoting of a square matrix (dgetrf), kept for repeated solves: the bordered
// refits of a drag (hrbf_sample_drag.h) factorise once and solve many times.
class DenseLu {
 public:
  // Throws NumericalError when a pivot is exactly zero (singular) or K is not finite.
  explicit DenseLu(Eigen::MatrixXd K);
  // rhs ← K⁻¹ rhs, for any number of columns (triangular solves in Eigen on the factors).
  void solveInPlace(Eigen::MatrixXd& rhs) const;
  void solveInPlace(Eigen::VectorXd& rhs) const;

 private:
  Eigen::MatrixXd lu_;
  std::vector<int> pivots_;
};

// Estimate of ‖M⁻¹‖₁ for an n × n symmetric matrix M known only through solves (`solve`
// overwrites v with M⁻¹v): the Hager–Higham estimator of LAPACK's dlacn2, 4–5 solves typically.
double symmetricInverseNormEstimate(Eigen::Index n, const std::function<void(Eigen::VectorXd&)>& solve);

}  // namespace hermite
