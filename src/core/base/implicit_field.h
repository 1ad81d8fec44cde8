#pragma once
// The interface render/ and meshing consume: any scalar field f with gradient and Hessian.
// Convention (docs/maths.md, Conventions): f < 0 inside, f > 0 outside, ∇f points outward.

#include <memory>
#include <vector>

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

  // Whether f at x rests on data ("no data" otherwise: e.g. a partition-of-unity point that no
  // box holding samples covers). Where it is false f is a finite stand-in (docs/maths.md,
  // "No data") that the mesh export, the tracers and the 2D view never show as surface.
  virtual bool valid(const Vec<Dim>& x) const {
    (void)x;
    return true;
  }
  // valid() for a consumer that samples f on a grid whose cells have diagonal `margin` (world
  // units, ≥ 0) and makes geometry in a cell only where all its corners are valid: a field whose
  // data reach can be thinner than a cell widens it by up to `margin` there, so every corner of a
  // cell the zero set crosses near the data is valid (docs/maths.md, "No data"). valid(x) by default.
  virtual bool validNear(const Vec<Dim>& x, double margin) const {
    (void)margin;
    return valid(x);
  }
  // Whether a point x of the zero set (a contour vertex) rests on data: may be stricter than
  // valid(), since the surface runs through its samples, so an open surface ends nearer its last
  // samples than the field's data reach (docs/maths.md, "No data"). valid(x) by default.
  virtual bool validOnZeroSet(const Vec<Dim>& x) const { return valid(x); }
  // valid() (margin 0) or validNear(·, margin) at the columns of X (Dim × N) into out (N entries,
  // 1 = valid), in parallel. A field from forGridCells may answer 2: valid only through its
  // extension beyond the data (a cell with such a corner keeps a polygon only when all its
  // vertices have data). Overrides keep the default margin 0.
  virtual void validBatch(const Points<Dim>& X, std::vector<char>& out, double margin = 0.0) const;
  // validOnZeroSet() at the columns of X (Dim × N) into out (N entries, 1 = valid), in parallel.
  void validOnZeroSetBatch(const Points<Dim>& X, std::vector<char>& out) const;
  // f and valid() at the columns of X in one pass where the field can share the work (the
  // partition of unity finds its supports once); by default evaluateBatch then validBatch.
  virtual void evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f, std::vector<char>& valid) const;
  // False when valid() may return false somewhere (callers skip the validity pass otherwise).
  virtual bool everywhereValid() const { return true; }
  // The field as a contour of a grid with cells of diagonal `cellDiagonal` (world units) reads it,
  // or null for the field itself: a field whose values end where its data ends (a partition of
  // unity's supports) gives f a value up to a cell beyond, so that every corner of a cell its zero
  // set crosses near the data has one (docs/maths.md, "No data").
  virtual std::unique_ptr<ImplicitField<Dim>> forGridCells(double cellDiagonal) const {
    (void)cellDiagonal;
    return nullptr;
  }

  // L ≥ sup over the box of ‖∇f‖: |f(x) − f(y)| ≤ L‖x − y‖ inside the box (safe ray steps).
  virtual double lipschitzBound(const Box<Dim>& box) const = 0;

  // The field as one global sum of kernels, when it is one (null otherwise): the tracer uploads
  // its centres and coefficients to the GPU and the bake has a fused loop for it.
  virtual const RadialSum<Dim>* asRadialSum() const { return nullptr; }
};

extern template class ImplicitField<2>;
extern template class ImplicitField<3>;

}  // namespace hermite
