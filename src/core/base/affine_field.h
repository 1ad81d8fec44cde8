#pragma once
// The exact composition g(x) = f(A⁻¹(x − b)) of a field with an invertible affine map
// T(x) = A·x + b: the transforms outside the similarity family (non-uniform scale, shear).
// ∇g(x) = A⁻ᵀ ∇f(y) and Hg(x) = A⁻ᵀ Hf(y) A⁻¹ at y = T⁻¹(x). This is a moved copy of f, not the
// interpolant of the transformed data: the normals of the transformed samples are A⁻ᵀnᵢ (not unit)
// and kernels are not invariant under such maps. The UI says so.

#include <memory>

#include "core/base/implicit_field.h"

namespace hermite {

template <int Dim>
class AffineComposedField final : public ImplicitField<Dim> {
 public:
  // Throws InputError when A is singular.
  AffineComposedField(std::shared_ptr<const ImplicitField<Dim>> field, const Mat<Dim>& A, const Vec<Dim>& b);

  double evaluate(const Vec<Dim>& x, Vec<Dim>* g = nullptr, Mat<Dim>* H = nullptr) const override;
  void evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G = nullptr) const override;
  bool valid(const Vec<Dim>& x) const override { return field_->valid(Ainv_ * (x - b_)); }
  // A world margin is at most ‖A⁻¹‖₂ times it in the inner field's coordinates.
  bool validNear(const Vec<Dim>& x, double margin) const override {
    return field_->validNear(Ainv_ * (x - b_), margin * inverseNorm_);
  }
  bool validOnZeroSet(const Vec<Dim>& x) const override { return field_->validOnZeroSet(Ainv_ * (x - b_)); }
  bool everywhereValid() const override { return field_->everywhereValid(); }
  // L_f over the box's preimage (its bounding box) times ‖A⁻¹‖₂ (‖∇g‖ ≤ ‖A⁻ᵀ‖‖∇f‖).
  double lipschitzBound(const Box<Dim>& box) const override;

  const ImplicitField<Dim>& inner() const { return *field_; }
  const Mat<Dim>& linear() const { return A_; }
  const Vec<Dim>& offset() const { return b_; }

 private:
  std::shared_ptr<const ImplicitField<Dim>> field_;
  Mat<Dim> A_, Ainv_;
  Vec<Dim> b_;
  double inverseNorm_ = 1;  // ‖A⁻¹‖₂
};

extern template class AffineComposedField<2>;
extern template class AffineComposedField<3>;

}  // namespace hermite
