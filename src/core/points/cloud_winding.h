#pragma once
// The winding number of an oriented point cloud: which side of the sampled surface a point lies
// on, read from the samples alone (docs/maths.md, "Stray pockets"). Each sample stands for a
// small patch of area aᵢ with normal nᵢ, and the patches add up as dipoles:
//
//   w(x) = Σᵢ aᵢ (pᵢ − x)·nᵢ / (4π (‖pᵢ − x‖² + εᵢ²)^{3/2})    (3D; aᵢ an area)
//   w(x) = Σᵢ aᵢ (pᵢ − x)·nᵢ / (2π (‖pᵢ − x‖² + εᵢ²))          (2D; aᵢ a length)
//
// aᵢ is the share of the surface around sample i: from dₖ, its distance to the k-th nearest
// other sample (k = 12 in 3D, 4 in 2D; capped at twice the median), aᵢ = π dₖ²/k in 3D (k
// samples in a disc of radius dₖ) and 2dₖ/k in 2D. Exact on average for random samples; on a
// lattice-like sampling within about 15 %. εᵢ = ½hᵢ (hᵢ = √aᵢ, or aᵢ in 2D, the spacing) softens the sum
// near a sample. For a densely sampled closed surface w is about 1 inside and 0 outside from
// about one spacing off the surface on, and passes ½ on it; within half a spacing it stays
// between 0.3 and 0.7. A box of samples far from x counts by the expansion of its dipoles about
// its area-weighted centre, to second order in the samples' offsets from it (Barnes–Hut: a box of
// radius R at distance d > 3R). Near a sampled surface that is within 0.03 of the direct sum
// (CGAL's cheese, elephant and Stanford dragon at 200 000 samples, 3 000 points up to 3 spacings
// off them; the first-order sum beyond 2R was off by up to 0.2, and put 15 % of the cheese's
// points on the wrong side of 0.15 or 0.85).

#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/geometry.h"

namespace hermite {

template <int Dim>
class CloudWinding {
 public:
  // Points and unit normals are Dim × N (N ≥ 1, the same N). `cancel` is polled while the
  // spacings are measured (Cancelled).
  CloudWinding(const Points<Dim>& points, const Points<Dim>& normals, const CancelToken* cancel = nullptr);

  // w(x), world units.
  double at(const Vec<Dim>& x) const;
  // w at the columns of X (Dim × M), in parallel.
  std::vector<double> at(const Points<Dim>& X) const;
  // w(x) summed over every sample, without the far field's expansion: O(N), for checks.
  double directAt(const Vec<Dim>& x) const;
  int size() const { return static_cast<int>(points_.cols()); }

 private:
  struct Node {
    Vec<Dim> centre;  // area-weighted centre of the node's samples
    Vec<Dim> moment;  // Σ aᵢ nᵢ
    Eigen::Matrix<double, Dim, Dim> spread;  // Σ aᵢ nᵢ (pᵢ − centre)ᵀ: the expansion's second term
    double radius = 0;  // largest distance of a sample from `centre`
    int begin = 0, end = 0;  // samples points_.col(begin … end − 1)
    int left = -1;   // children left, left + 1; −1 for a leaf
  };
  // Builds nodes_ over the columns of `points`; returns the tree order (sample index per slot).
  std::vector<int> buildTree(const Points<Dim>& points);
  // Orders node's range of `order` about its median along the longest axis of its samples' box;
  // false (nothing changed) for a leaf of at most kLeafSamples samples.
  static bool splitAtMedian(const Points<Dim>& points, const Node& node, std::vector<int>& order);
  void summarise(Node& node) const;
  // Σ over the samples begin … end − 1 (tree order) of their softened dipoles at x.
  double directSum(const Vec<Dim>& x, int begin, int end) const;

  Points<Dim> points_, normals_;  // in tree order
  std::vector<double> area_, soft2_;  // aᵢ, εᵢ² in tree order
  std::vector<Node> nodes_;           // nodes_[0] is the root
};

extern template class CloudWinding<2>;
extern template class CloudWinding<3>;

}  // namespace hermite
