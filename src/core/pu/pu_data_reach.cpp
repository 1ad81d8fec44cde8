#include "core/pu/pu_data_reach.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/base/errors.h"

namespace hermite {

namespace {

// dₖ of the samples of one leaf (k = 2·Dim): the k-th smallest positive distance to the samples
// of the leaf box scaled by 2, grown ×2 while it holds too few others. Beyond the scaled box a
// neighbour may be missed, which only overestimates dₖ (a wider reach, never a hole).
template <int Dim>
void leafSpacings(const PuTree<Dim>& tree, int leaf, std::vector<double>& radius, std::vector<int>& cand) {
  constexpr int k = 2 * Dim;
  const int node = tree.leaves()[static_cast<std::size_t>(leaf)];
  const auto& nd = tree.node(node);
  const Box<Dim>& root = tree.root();
  const Points<Dim>& Y = tree.sortedPoints();
  double scale = 2.0;
  for (;;) {
    tree.positionsInBox(scaledBox<Dim>(tree.leafBox(leaf), scale), cand, node);
    const bool all = (scaledBox<Dim>(tree.leafBox(leaf), scale).extent().array() >= root.extent().array()).all();
    if (static_cast<int>(cand.size()) > 2 * k || all) break;
    scale *= 2.0;
  }
  const double fallback = root.extent().norm();  // a lone sample reaches the whole root box
  // The k smallest squared distances, kept sorted as the candidates pass, and the square root of
  // the k-th (of the largest when fewer): norm() is the square root of squaredNorm() and the
  // rounded square root is monotonic, so dₖ is the k-th smallest distance, bit for bit.
  for (int j = nd.begin; j < nd.end; ++j) {
    const Vec<Dim> p = Y.col(j);
    double best[k];
    int have = 0;
    for (int c : cand) {
      const double d2 = (Y.col(c) - p).squaredNorm();
      if (!(d2 > 0) || (have == k && d2 >= best[k - 1])) continue;  // coincident samples give no spacing
      int at = have < k ? have++ : k - 1;
      for (; at > 0 && best[at - 1] > d2; --at) best[at] = best[at - 1];
      best[at] = d2;
    }
    radius[static_cast<std::size_t>(j)] = have > 0 ? std::sqrt(best[have - 1]) : fallback;
  }
}

// rᵢ is at most kSpacingCap times the median dₖ (times c): a sample whose k-th neighbour is far —
// an isolated sample, or a single row of samples such as the sparse rim of a scan (oni.pwn's
// neck: dₖ of 3 steps along the row, 5 times the median) — would otherwise reach a fifth of the
// data across.
constexpr double kSpacingCap = 2.0;

// Within kInnerReach·rᵢ of its nearest sample y has data whatever the edge test says: the test
// assumes the surface flat across the reach, which a thin limb's tip is not (there it would
// open holes), and half a reach past the last samples is no sheet.
constexpr double kInnerReach = 0.5;

}  // namespace

template <int Dim>
PuDataReach<Dim>::PuDataReach(const PuTree<Dim>& tree, const Points<Dim>& frameY, double factor,
                              const Points<Dim>* frameNormals, double edgeShift, const CancelToken* cancel) {
  if (!(factor > 0) || !std::isfinite(factor)) throw InputError("partition: data_reach must be a finite number > 0");
  if (!(edgeShift >= 0) || !std::isfinite(edgeShift))
    throw InputError("partition: the edge shift must be a finite number >= 0");
  factor_ = factor;
  const auto& order = tree.order();
  const int n = static_cast<int>(order.size());
  points_.resize(Dim, n);
  for (int j = 0; j < n; ++j) points_.col(j) = frameY.col(order[static_cast<std::size_t>(j)]);
  if (frameNormals && edgeShift > 0) {
    edgeShift_ = edgeShift;
    normals_.resize(Dim, n);
    for (int j = 0; j < n; ++j) {
      const Vec<Dim> nj = frameNormals->col(order[static_cast<std::size_t>(j)]);
      const double len = nj.norm();
      normals_.col(j) = len > 0 ? Vec<Dim>(nj / len) : Vec<Dim>::Zero();  // zero: no tangent plane there
    }
  }
  radius_.assign(static_cast<std::size_t>(n), 0.0);
  const int leaves = tree.leafCount();
#pragma omp parallel
  {
    std::vector<int> cand;
#pragma omp for schedule(dynamic, 16)
    for (int i = 0; i < leaves; ++i)  // no throw inside the parallel loop: cancelled leaves are skipped
      if (tree.leafSampleCount(i) > 0 && !(cancel && cancel->cancelled()))
        leafSpacings<Dim>(tree, i, radius_, cand);
  }
  throwIfCancelled(cancel);
  if (n > 0) {
    std::vector<double> sorted = radius_;
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
    const double cap = kSpacingCap * sorted[static_cast<std::size_t>(n / 2)];
    for (double& r : radius_) r = std::min(r, cap);
  }
  for (double& r : radius_) r *= factor;
  const auto& nodes = tree.nodes();
  nodeRadius_.assign(nodes.size(), 0.0);
  for (std::size_t id = 0; id < nodes.size(); ++id)
    for (int j = nodes[id].begin; j < nodes[id].end; ++j)
      nodeRadius_[id] = std::max(nodeRadius_[id], radius_[static_cast<std::size_t>(j)]);
}

template <int Dim>
bool PuDataReach<Dim>::reaches(const PuTree<Dim>& tree, const Vec<Dim>& y, double margin, double scale) const {
  if (radius_.empty()) return true;
  // ρ(r) = max(σr, r/c + δ) grows with r, so a node's bound is ρ of its largest radius.
  const double invC = 1.0 / factor_;
  const auto widened = [&](double r) { return margin > 0 ? std::max(scale * r, r * invC + margin) : scale * r; };
  const bool edgeTest = normals_.cols() > 0;
  // Over the reaching samples i: their count, Σ vᵢ and Σ vᵢvᵢᵀ with vᵢ = pᵢ − y, and the nearest.
  int count = 0, nearest = -1;
  double nearestSq = std::numeric_limits<double>::infinity();
  Vec<Dim> sumV = Vec<Dim>::Zero();
  Mat<Dim> sumVV = Mat<Dim>::Zero();
  const auto& nodes = tree.nodes();
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int id = stack[--top];
    const auto& nd = nodes[static_cast<std::size_t>(id)];
    const double r = widened(nodeRadius(static_cast<std::size_t>(id)));  // 0 for nodes split off later
    if (nd.begin == nd.end || normExceeds(squaredDistanceTo<Dim>(nd.box, y), r)) continue;
    if (nd.firstChild >= 0) {
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
      continue;
    }
    for (int j = nd.begin; j < nd.end; ++j) {
      const double rj = widened(radius_[static_cast<std::size_t>(j)]);
      const Vec<Dim> v = points_.col(j) - y;
      const double sq = v.squaredNorm();
      if (sq > rj * rj) continue;
      if (!edgeTest) return true;
      ++count;
      sumV += v;
      sumVV += v * v.transpose();
      if (sq < nearestSq) {
        nearestSq = sq;
        nearest = j;
      }
    }
  }
  if (count == 0) return false;
  const double inner = kInnerReach * widened(radius_[static_cast<std::size_t>(nearest)]);
  if (nearestSq <= inner * inner) return true;
  // The tangential mean offset s = P·m (m = Σv/count, P = I − nnᵀ) against the samples' standard
  // deviation σ along it: |s| ≤ z·σ with σ² = ŝᵀ(M/count)ŝ − |s|² (M = Σvvᵀ, ŝ = s/|s|; Ps = s
  // and s·m = |s|²), squared and multiplied out: (1 + z²)|s|⁴ ≤ z²·sᵀ(M/count)s.
  const Vec<Dim> n = normals_.col(nearest);
  const Vec<Dim> m = sumV / count;
  const Vec<Dim> shift = m - n * n.dot(m);
  const double s2 = shift.squaredNorm();
  const double z2 = edgeShift_ * edgeShift_;
  return (1 + z2) * s2 * s2 <= z2 * shift.dot(sumVV * shift) / count;
}

template class PuDataReach<2>;
template class PuDataReach<3>;

}  // namespace hermite
