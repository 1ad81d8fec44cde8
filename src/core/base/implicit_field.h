#pragma once
// The interface render/ and meshing consume: any scalar field f with gradient and Hessian.
// Convention (docs/maths.md, Conventions): f < 0 inside, f > 0 outside, ∇f points outward.

#include "core/base/geometry.h"

namespace hermite {

// Declared in core/rbf/radial_sum.h; named here only so a field can say that it is one.
template <int Dim>
class RadialSum;

template <int Dim>
class ImplicitField {
 public:
  virtual ~ImplicitField() = default;

  // f(x); and, when g / H are not null, ∇f(x) and the Hessian.
  virtual double evaluate(const Vec<Dim>& x, Vec<Dim>* g = nullptr, Mat<Dim>* H = nullptr) const = 0;

  double value(const Vec<Dim>& x) const { return evaluate(x); }
  Vec<Dim> gradient(const Vec<Dim>& x) const {
    Vec<Dim> g;
    evaluate(x, &g);
    return g;
  }
  Mat<Dim> hessian(const Vec<Dim>& x) const {
    Vec<Dim> g;
    Mat<Dim> H;
    evaluate(x, &g, &H);
    return H;
  }

  // Batch evaluation of f (N) and, when G is not null, ∇f (Dim × N) at the columns of X
  // (Dim × N), in parallel over points. Fields override it with vectorised loops.
  virtual void evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G = nullptr) const;

  // L ≥ sup over the box of ‖∇f‖: |f(x) − f(y)| ≤ L‖x − y‖ inside the box (safe ray steps).
  virtual double lipschitzBound(const Box<Dim>& box) const = 0;

  // The field as one global sum of kernels, when it is one (null otherwise): the tracer uploads
  // its centres and coefficients to the GPU and the bake has a fused loop for it.
  virtual const RadialSum<Dim>* asRadialSum() const { return nullptr; }
};

extern template class ImplicitField<2>;
extern template class ImplicitField<3>;

}  // namespace hermite
