#pragma once
// Where a partition-of-unity field rests on data (docs/maths.md, "No data"): within reach of the
// samples, MPU-style, and not past the edge of the data:
//
//   reaches(y)  ⇔  R(y) ≠ ∅  and (edge test)  |s| ≤ z·σ,
//   R(y) = { i : ‖y − pᵢ‖ ≤ rᵢ },   rᵢ = c · dₖ(pᵢ),
//
// with pᵢ the samples in frame coordinates, dₖ(pᵢ) the distance to the k-th nearest other
// distinct sample (k = 2·Dim: about 1.4 spacings on a surface, 2 along a curve) — the local
// spacing, so the reach follows the sampling density — capped at twice the median dₖ, and
// c = PuOptions::dataReach.
// The edge test (only with z = PuOptions::edgeShift > 0; off by default) applies beyond half a
// reach from the nearest sample: s = P·mean_{i∈R(y)}(pᵢ − y) is the reaching samples' mean
// offset along the tangent plane of the sample nearest to y (normal n: P = I − nnᵀ), σ the
// standard deviation of their offsets along s. Inside a sampled surface the reaching samples
// surround y (s ≈ 0); at an open edge they fill half a disc (|s| = 1.6·σ) and beyond it a
// thinner slice (|s|/σ grows without bound), so a surface ends a fraction of the reach past its
// last samples. Sharp edges (0.7·σ), convex box corners (1.6·σ) and points off the surface
// along n pass; the tips of limbs thinner than the reach may not (docs/maths.md, "No data").
// Queries walk the box tree, pruning nodes whose samples' largest radius cannot reach y.

#include <cmath>
#include <vector>

#include "core/pu/pu_tree.h"

namespace hermite {

// √s > r for s the squared norm of a vector and r ≥ 0, exactly as the rounded square root
// compares (norm() is the square root of squaredNorm()), taking the root only when s lies
// within a relative 10⁻¹² of r²: the reach tests compare millions of distances with radii.
inline bool normExceeds(double squaredNorm, double r) {
  const double r2 = r * r;
  if (squaredNorm > r2 * (1 + 1e-12)) return true;
  if (squaredNorm < r2 * (1 - 1e-12)) return false;
  return std::sqrt(squaredNorm) > r;
}

// The squared distance from x to the nearest point of the box b (0 inside): Box::distanceTo
// before its square root.
template <int Dim>
double squaredDistanceTo(const Box<Dim>& b, const Vec<Dim>& x) {
  return (b.lo - x).cwiseMax(x - b.hi).cwiseMax(Vec<Dim>::Zero()).squaredNorm();
}

template <int Dim>
class PuDataReach {
 public:
  PuDataReach() = default;  // reaches everywhere (no samples recorded)
  // The reach of the samples `frameY` (Dim × N, the tree's points) with factor c > 0. With
  // `frameNormals` (Dim × N, non-zero, frame coordinates) and edgeShift z > 0 the edge test
  // applies too; without them (or β = 0) the reach alone decides. `cancel` is polled per leaf
  // (Cancelled after the loop).
  PuDataReach(const PuTree<Dim>& tree, const Points<Dim>& frameY, double factor,
              const Points<Dim>* frameNormals = nullptr, double edgeShift = 0.0,
              const CancelToken* cancel = nullptr);

  bool empty() const { return radius_.empty(); }
  // Whether y (frame coordinates) has data: some sample reaches it and it is not past the edge
  // of the data; true when empty(). With margin δ > 0 (a grid's cell diagonal, frame units) the
  // reach of sample i is ρᵢ = max(rᵢ, rᵢ/c + δ): a zero set passing within the capped spacing
  // rᵢ/c of pᵢ has every corner of each grid cell it crosses there within ρᵢ of pᵢ, whatever the
  // ratio of the spacing to the grid step (docs/maths.md, "No data").
  // With scale σ (0 < σ ≤ 1) every reach rᵢ is σ·rᵢ first (the zero-set reach, σ = β/c).
  bool reaches(const PuTree<Dim>& tree, const Vec<Dim>& y, double margin = 0.0, double scale = 1.0) const;
  // c of rᵢ = c·dₖ.
  double factor() const { return factor_; }
  // rᵢ of the sample at position j of tree.order(), frame units.
  double radiusAt(int j) const { return radius_[static_cast<std::size_t>(j)]; }
  // The largest rᵢ of tree node id's samples: 0 for a node without samples, including nodes
  // added to the tree after this reach was built (PuTree::splitEmptyLeaves adds only empty ones).
  double nodeRadius(std::size_t id) const { return id < nodeRadius_.size() ? nodeRadius_[id] : 0.0; }
  // Largest rᵢ over all samples (0 when empty).
  double maxRadius() const { return nodeRadius_.empty() ? 0.0 : nodeRadius_.front(); }

 private:
  Points<Dim> points_;              // Dim × N in tree order: node samples are contiguous
  Points<Dim> normals_;             // Dim × N unit normals in tree order; empty: no edge test
  std::vector<double> radius_;      // N, in tree order
  std::vector<double> nodeRadius_;  // per tree node: the largest radius of its samples (0 if none)
  double edgeShift_ = 0.0;          // z of the edge test
  double factor_ = 1.0;             // c: rᵢ / c is the sample's capped spacing
};

extern template class PuDataReach<2>;
extern template class PuDataReach<3>;

}  // namespace hermite
