#pragma once
// A global fit's field with the samples' data reach as its validity (docs/maths.md, "No data":
// the partition of unity's reach, PuDataReach): beyond c·dₖ of every sample the field has "no
// data", so the mesh export, the tracers and the 2D view end an open scan's surface near its last
// samples instead of following the global interpolant's continuation to view.bounds. f and ∇f
// are the inner field's; a grid consumer's margin and the zero set's narrower reach (β capped
// spacings) apply as they do for the partition of unity.

#include <memory>

#include "core/base/masked_field.h"
#include "core/pu/pu_data_reach.h"
#include "core/pu/pu_tree.h"

namespace hermite {

template <int Dim>
class ReachMaskedField final : public MaskedField<Dim> {
 public:
  // The reach of `points` (Dim × N, N ≥ 1, the world positions the inner field interpolates)
  // with factor c = `reach` > 0 and zero-set reach β = `vertexReach` > 0 capped spacings.
  // `inner` must outlive this field unless it is `owned` (then inner is *owned).
  ReachMaskedField(const ImplicitField<Dim>& inner, const Points<Dim>& points, double reach, double vertexReach,
                   std::unique_ptr<ImplicitField<Dim>> owned = nullptr);

  bool valid(const Vec<Dim>& x) const override { return validNear(x, 0.0); }
  bool validNear(const Vec<Dim>& x, double margin) const override;
  bool validOnZeroSet(const Vec<Dim>& x) const override;
  void evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f, std::vector<char>& valid) const override;

 private:
  PuTree<Dim> tree_;  // the samples' boxes: what the reach queries walk
  PuDataReach<Dim> reach_;
  double zeroSetScale_;  // β / c, at most 1
};

extern template class ReachMaskedField<2>;
extern template class ReachMaskedField<3>;

}  // namespace hermite
