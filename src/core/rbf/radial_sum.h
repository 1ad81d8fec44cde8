#pragma once
// The evaluator shared by HRBF and RBF-offset models:
//   f(x) = Σⱼ αⱼ φ(‖x − cⱼ‖) − βⱼ·∇φ(x − cⱼ) + p(x − o)     (β empty: plain RBF; o: polyOrigin)
// with value / gradient / Hessian at a point, vectorised batch evaluation and Lipschitz bounds.

#include "core/base/implicit_field.h"
#include "core/rbf/kernels.h"
#include "core/rbf/polynomial.h"

namespace hermite {

template <int Dim>
class RadialSum : public ImplicitField<Dim> {
 public:
  RadialSum() = default;
  // `polyOrigin`: the point the polynomial part is written about, p(x − polyOrigin)
  // (exact_centre.h; zero for data near the origin).
  RadialSum(Kernel kernel, Polynomial polynomial, Points<Dim> centres, Eigen::VectorXd alpha,
            Points<Dim> beta, Eigen::VectorXd poly, Vec<Dim> polyOrigin = Vec<Dim>::Zero());

  double evaluate(const Vec<Dim>& x, Vec<Dim>* g = nullptr, Mat<Dim>* H = nullptr) const override;
  void evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G = nullptr) const override;
  double lipschitzBound(const Box<Dim>& box) const override;
  const RadialSum<Dim>* asRadialSum() const override { return this; }
  // Σⱼ |αⱼ φ(‖x − cⱼ‖)| + |βⱼ·∇φ(x − cⱼ)| + Σ |each polynomial monomial term| at x: the size of
  // the terms that cancel into f(x). Rounding of a sum in precision u errs by about u times this
  // (times a slowly growing factor in N), so it says whether float evaluation is good enough.
  double termMagnitude(const Vec<Dim>& x) const;

  const Kernel& kernel() const { return kernel_; }
  Polynomial polynomial() const { return polynomial_; }
  const Points<Dim>& centres() const { return centres_; }  // Dim × N
  const Eigen::VectorXd& alpha() const { return alpha_; }   // N
  const Points<Dim>& beta() const { return beta_; }         // Dim × N, or Dim × 0 (plain RBF)
  const Eigen::VectorXd& poly() const { return poly_; }     // m, order of polynomial.h
  const Vec<Dim>& polyOrigin() const { return polyOrigin_; }  // the polynomial is p(x − polyOrigin)
  bool hasBeta() const { return beta_.cols() > 0; }

 private:
  void buildSoA();

  Kernel kernel_;
  Polynomial polynomial_ = Polynomial::None;
  Points<Dim> centres_;
  Eigen::VectorXd alpha_;
  Points<Dim> beta_;
  Eigen::VectorXd poly_;
  Vec<Dim> polyOrigin_ = Vec<Dim>::Zero();
  // Structure-of-arrays copies padded to a multiple of 8 (padding: zero coefficients) for the
  // vectorised loops, in one buffer of 2·Dim + 1 rows of padded_ entries: soa(k) holds coordinate
  // k of every centre, soa(Dim) α, soa(Dim + 1 + k) βₖ.
  const double* soa(int row) const { return soa_.data() + static_cast<std::size_t>(row) * padded_; }
  std::vector<double> soa_;
  int padded_ = 0;
};

extern template class RadialSum<2>;
extern template class RadialSum<3>;

}  // namespace hermite
