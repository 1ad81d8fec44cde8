#pragma once
// A field with its flat regions (degenerate_field.h) marked as "no data" (ImplicitField::valid):
// the marcher makes no contour there, the 2D view hatches them and the CPU tracer treats them as
// outside — the mechanism the partition of unity's uncovered points use — so the noise-signed
// zero set of a degenerate field is never shown or exported as surface. f and ∇f are the inner
// field's.

#include <memory>

#include "core/base/implicit_field.h"
#include "core/mesh/degenerate_field.h"

namespace hermite {

template <int Dim>
class FlatMaskedField final : public ImplicitField<Dim> {
 public:
  // `inner` must outlive this field unless it is `owned` (then inner is *owned).
  FlatMaskedField(const ImplicitField<Dim>& inner, const FlatnessScale& scale,
                  std::unique_ptr<ImplicitField<Dim>> owned = nullptr)
      : owned_(std::move(owned)), inner_(inner), scale_(scale) {}

  double evaluate(const Vec<Dim>& x, Vec<Dim>* g = nullptr, Mat<Dim>* H = nullptr) const override {
    return inner_.evaluate(x, g, H);
  }
  void evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G = nullptr) const override {
    inner_.evaluateBatch(X, f, G);
  }
  bool valid(const Vec<Dim>& x) const override;
  bool validNear(const Vec<Dim>& x, double margin) const override;
  bool validOnZeroSet(const Vec<Dim>& x) const override { return inner_.validOnZeroSet(x) && valid(x); }
  void evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f, std::vector<char>& valid) const override;
  bool everywhereValid() const override { return false; }
  double lipschitzBound(const Box<Dim>& box) const override { return inner_.lipschitzBound(box); }
  // No RadialSum: the GPU paths draw a radial sum without validity.
  const RadialSum<Dim>* asRadialSum() const override { return nullptr; }

 private:
  std::unique_ptr<ImplicitField<Dim>> owned_;
  const ImplicitField<Dim>& inner_;
  FlatnessScale scale_;
};

extern template class FlatMaskedField<2>;
extern template class FlatMaskedField<3>;

}  // namespace hermite
