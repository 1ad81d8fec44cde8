#pragma once
// Refits of an HRBF while one sample moves or its normal turns (the GUI's drag), in O(n²) per
// refit instead of the O(n³) factorisation of fitHrbf.
//
// Order the unknowns as R (every other sample's α, β and the polynomial coefficients) and I
// (the moved sample's α, β). The system is the bordered matrix
//
//   [ K_RR   K_RI ] [x_R]   [b_R]        K_RR: the HRBF system of the other samples — it does
//   [ K_IR   K_II ] [x_I] = [b_I]        not depend on the moved sample, so it is factorised
//                                         once (LU with partial pivoting) when the drag begins;
//
// K_RI (= K_IRᵀ) couples the moved sample with the rest (hrbfBlock, hrbfPolynomialRows) and
// K_II is its own (Dim+1)² block. Each refit solves through the Schur complement
// S = K_II − K_IR K_RR⁻¹ K_RI: Dim + 1 solves with the kept factors plus a (Dim+1)² system, then
// one step of iterative refinement on the whole system. The result is checked: a residual
// above 1e-9 of the system's scale is a NumericalError (the caller then fits from scratch).
//
// The GUI factorises when a sample is grabbed (app/gui/drag_refit.h); docs/performance.md has the
// factorisation and per-refit times against fitHrbf (`hermite-lab bench --only gui/drag-latency`).

#include <chrono>
#include <optional>

#include <Eigen/LU>

#include "core/rbf/dense_solver.h"
#include "core/rbf/hrbf.h"

namespace hermite {

template <int Dim>
class HrbfBorderedRefit {
 public:
  // Factorises the system of every sample but `moved`. Throws InputError for an index out of
  // range or bad options (as fitHrbf), NumericalError when the other samples alone give a
  // singular system (then the caller fits from scratch on every move).
  HrbfBorderedRefit(const HermiteSamples<Dim>& samples, const HrbfOptions& options, int moved);

  // The HRBF of the construction's samples with sample `moved` at `point` with normal
  // `normal`. `report` gets solver "bordered-lu", the 1-norm condition estimate of the whole
  // system and the warnings fitHrbf would give. Throws NumericalError when the bordered solve
  // is singular or not accurate.
  HrbfModel<Dim> fit(const Vec<Dim>& point, const Vec<Dim>& normal, FitReport* report = nullptr) const;

  int moved() const { return moved_; }

 private:
  static constexpr int B = Dim + 1;  // unknowns per centre, conditions per sample
  using Border = Eigen::Matrix<double, Eigen::Dynamic, B>;
  using Block = Eigen::Matrix<double, B, B>;

  using BVec = Eigen::Matrix<double, B, 1>;
  // The moved sample's part of K for one move: K_RI, K_II, Y = K_RR⁻¹ K_RI and the LU of the
  // Schur complement S = K_II − K_IR Y.
  struct Bordered {
    Border Kri;
    Block Kii;
    Border Y;
    Eigen::PartialPivLU<Block> schur;
  };
  // K_RI and K_II for the moved sample at `point`; throws NumericalError for non-finite entries.
  Bordered assembleBorder(const Vec<Dim>& point) const;
  // Y and the Schur complement's LU; throws NumericalError when S is singular.
  void factorBorder(Bordered& k) const;
  // The full solve K x = rhs through the Schur complement (rhs split as R, I).
  void solveBordered(const Bordered& k, Eigen::VectorXd& rhsR, BVec& rhsI) const;
  // One step of iterative refinement of x = (xR, xI), then the residual check (NumericalError
  // when inaccurate). Returns ‖K‖∞.
  double refineAndCheck(const Bordered& k, const BVec& bI, Eigen::VectorXd& xR, BVec& xI) const;
  // The model in fitHrbf's layout: centres in the samples' order, the moved one in its place.
  HrbfModel<Dim> model(const Vec<Dim>& point, const Eigen::VectorXd& xR, const BVec& xI) const;

  HermiteSamples<Dim> samples_;
  HrbfOptions options_;
  int moved_ = 0;
  Eigen::MatrixXd Krr_;  // kept for the residual and the norm (the factors overwrite a copy)
  std::optional<DenseLu> lu_;
  Eigen::VectorXd bR_;  // right-hand side of the rest: normals of the other samples, zeros
  Eigen::VectorXd zR_;  // K_RR⁻¹ b_R
  Eigen::VectorXd krrColumnSums_;  // Σᵢ |K_RR(i, j)| for the 1-norm of K
};

}  // namespace hermite
