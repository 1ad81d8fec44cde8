#pragma once
// A field whose values are another's and whose validity ("no data", ImplicitField::valid) is its
// own: the base of the no-data masks (a degenerate field's flat regions, a global fit's data
// reach). f, ∇f and the Lipschitz bounds are the inner field's; the mask has no RadialSum, since
// the GPU tracer's exact shader sums one without validity (the GPU paths bake a masked field).

#include <memory>

#include "core/base/implicit_field.h"

namespace hermite {

template <int Dim>
class MaskedField : public ImplicitField<Dim> {
 public:
  double evaluate(const Vec<Dim>& x, Vec<Dim>* g = nullptr, Mat<Dim>* H = nullptr) const override {
    return inner_.evaluate(x, g, H);
  }
  void evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G = nullptr) const override {
    inner_.evaluateBatch(X, f, G);
  }
  bool everywhereValid() const override { return false; }
  double lipschitzBound(const Box<Dim>& box) const override { return inner_.lipschitzBound(box); }
  const RadialSum<Dim>* asRadialSum() const override { return nullptr; }

 protected:
  // `inner` must outlive this field unless it is `owned` (then inner is *owned).
  MaskedField(const ImplicitField<Dim>& inner, std::unique_ptr<ImplicitField<Dim>> owned)
      : owned_(std::move(owned)), inner_(inner) {}
  const ImplicitField<Dim>& inner() const { return inner_; }

 private:
  std::unique_ptr<ImplicitField<Dim>> owned_;
  const ImplicitField<Dim>& inner_;
};

}  // namespace hermite
