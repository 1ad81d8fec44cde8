#include "core/base/affine_field.h"

#include <Eigen/LU>
#include <Eigen/SVD>

#include "core/base/errors.h"

namespace hermite {

template <int Dim>
AffineComposedField<Dim>::AffineComposedField(std::shared_ptr<const ImplicitField<Dim>> field, const Mat<Dim>& A,
                                              const Vec<Dim>& b)
    : field_(std::move(field)), A_(A), b_(b) {
  const Eigen::FullPivLU<Mat<Dim>> lu(A);
  if (!lu.isInvertible()) throw InputError("affine transform: the linear part is singular");
  Ainv_ = lu.inverse();
  inverseNorm_ = Eigen::JacobiSVD<Mat<Dim>>(Ainv_).singularValues()(0);
}

template <int Dim>
double AffineComposedField<Dim>::evaluate(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H) const {
  const Vec<Dim> y = Ainv_ * (x - b_);
  Vec<Dim> gy;
  Mat<Dim> Hy;
  const double f = field_->evaluate(y, g || H ? &gy : nullptr, H ? &Hy : nullptr);
  if (g) *g = Ainv_.transpose() * gy;
  if (H) *H = Ainv_.transpose() * Hy * Ainv_;
  return f;
}

template <int Dim>
void AffineComposedField<Dim>::evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) const {
  const Points<Dim> Y = Ainv_ * (X.colwise() - b_);
  field_->evaluateBatch(Y, f, G);
  if (G) *G = Ainv_.transpose() * (*G);
}

template <int Dim>
double AffineComposedField<Dim>::lipschitzBound(const Box<Dim>& box) const {
  // The preimage of the box is a parallelepiped: bound it by the box of its corners.
  Box<Dim> pre;
  for (int c = 0; c < (1 << Dim); ++c) {
    Vec<Dim> corner;
    for (int k = 0; k < Dim; ++k) corner(k) = (c >> k) & 1 ? box.hi(k) : box.lo(k);
    const Vec<Dim> y = Ainv_ * (corner - b_);
    if (c == 0) pre.lo = pre.hi = y;
    pre.lo = pre.lo.cwiseMin(y);
    pre.hi = pre.hi.cwiseMax(y);
  }
  return field_->lipschitzBound(pre) * inverseNorm_;
}

template class AffineComposedField<2>;
template class AffineComposedField<3>;

}  // namespace hermite
