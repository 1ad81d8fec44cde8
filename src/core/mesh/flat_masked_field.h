#pragma once
// A field with its flat regions (degenerate_field.h) marked as "no data" (ImplicitField::valid):
// the marcher makes no contour there, the 2D view hatches them and the tracers pass the zeros
// there — the mechanism the partition of unity's uncovered points use — so the noise-signed zero
// set of a degenerate field is never shown or exported as surface. f and ∇f are the inner
// field's (MaskedField).

#include <memory>

#include "core/base/masked_field.h"
#include "core/mesh/degenerate_field.h"

namespace hermite {

template <int Dim>
class FlatMaskedField final : public MaskedField<Dim> {
 public:
  // `inner` must outlive this field unless it is `owned` (then inner is *owned).
  FlatMaskedField(const ImplicitField<Dim>& inner, const FlatnessScale& scale,
                  std::unique_ptr<ImplicitField<Dim>> owned = nullptr)
      : MaskedField<Dim>(inner, std::move(owned)), scale_(scale) {}

  bool valid(const Vec<Dim>& x) const override;
  bool validNear(const Vec<Dim>& x, double margin) const override;
  bool validOnZeroSet(const Vec<Dim>& x) const override { return this->inner().validOnZeroSet(x) && valid(x); }
  void evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f, std::vector<char>& valid) const override;

 private:
  FlatnessScale scale_;
};

extern template class FlatMaskedField<2>;
extern template class FlatMaskedField<3>;

}  // namespace hermite
