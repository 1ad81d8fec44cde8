#pragma once
// Where a partition-of-unity field rests on data (docs/maths.md, "No data"): within reach of a
// sample, MPU-style,
//
//   reaches(y)  ⇔  ∃ i: ‖y − pᵢ‖ ≤ rᵢ,   rᵢ = c · dₖ(pᵢ),
//
// with pᵢ the samples in frame coordinates, dₖ(pᵢ) the distance to the k-th nearest other
// distinct sample (k = 2·Dim: about 1.4 spacings on a surface, 2 along a curve) — the local
// spacing, so the reach follows the sampling density: thin on dense data, wide on sparse scans —
// and c = PuOptions::dataReach. Queries walk the box tree, pruning nodes whose samples' largest
// radius cannot reach y.

#include <vector>

#include "core/pu/pu_tree.h"

namespace hermite {

template <int Dim>
class PuDataReach {
 public:
  PuDataReach() = default;  // reaches everywhere (no samples recorded)
  // The reach of the samples `frameY` (Dim × N, the tree's points) with factor c > 0.
  PuDataReach(const PuTree<Dim>& tree, const Points<Dim>& frameY, double factor);

  bool empty() const { return radius_.empty(); }
  // Whether some sample reaches y (frame coordinates); true when empty().
  bool reaches(const PuTree<Dim>& tree, const Vec<Dim>& y) const;
  // rᵢ of the sample at position j of tree.order(), frame units.
  double radiusAt(int j) const { return radius_[static_cast<std::size_t>(j)]; }
  // Largest rᵢ over all samples (0 when empty).
  double maxRadius() const { return nodeRadius_.empty() ? 0.0 : nodeRadius_.front(); }

 private:
  Points<Dim> points_;              // Dim × N in tree order: node samples are contiguous
  std::vector<double> radius_;      // N, in tree order
  std::vector<double> nodeRadius_;  // per tree node: the largest radius of its samples (0 if none)
};

extern template class PuDataReach<2>;
extern template class PuDataReach<3>;

}  // namespace hermite
