#include "core/pu/pu_data_reach.h"

#include <algorithm>
#include <cmath>

#include "core/base/errors.h"

namespace hermite {

namespace {

// dₖ of the samples of one leaf: the k-th smallest positive distance to the samples of the leaf
// box scaled by 2, grown ×2 while it holds too few others. Beyond the scaled box a neighbour may
// be missed, which only overestimates dₖ (a wider reach, never a hole).
template <int Dim>
void leafSpacings(const PuTree<Dim>& tree, const Points<Dim>& frameY, int leaf, int k, std::vector<double>& radius,
                  std::vector<int>& cand, std::vector<double>& dist) {
  const auto& nd = tree.node(tree.leaves()[static_cast<std::size_t>(leaf)]);
  const Box<Dim>& root = tree.root();
  double scale = 2.0;
  for (;;) {
    tree.samplesInBox(frameY, scaledBox<Dim>(tree.leafBox(leaf), scale), cand);
    const bool all = (scaledBox<Dim>(tree.leafBox(leaf), scale).extent().array() >= root.extent().array()).all();
    if (static_cast<int>(cand.size()) > 2 * k || all) break;
    scale *= 2.0;
  }
  const double fallback = root.extent().norm();  // a lone sample reaches the whole root box
  for (int j = nd.begin; j < nd.end; ++j) {
    const Vec<Dim> p = frameY.col(tree.order()[static_cast<std::size_t>(j)]);
    dist.clear();
    for (int c : cand) {
      const double d = (frameY.col(c) - p).norm();
      if (d > 0) dist.push_back(d);  // coincident samples give no spacing
    }
    double dk = fallback;
    if (!dist.empty()) {
      const int rank = std::min(k, static_cast<int>(dist.size())) - 1;
      std::nth_element(dist.begin(), dist.begin() + rank, dist.end());
      dk = dist[static_cast<std::size_t>(rank)];
    }
    radius[static_cast<std::size_t>(j)] = dk;
  }
}

}  // namespace

template <int Dim>
PuDataReach<Dim>::PuDataReach(const PuTree<Dim>& tree, const Points<Dim>& frameY, double factor) {
  if (!(factor > 0) || !std::isfinite(factor)) throw InputError("partition: data_reach must be a finite number > 0");
  const auto& order = tree.order();
  const int n = static_cast<int>(order.size());
  points_.resize(Dim, n);
  for (int j = 0; j < n; ++j) points_.col(j) = frameY.col(order[static_cast<std::size_t>(j)]);
  radius_.assign(static_cast<std::size_t>(n), 0.0);
  constexpr int k = 2 * Dim;
  const int leaves = tree.leafCount();
#pragma omp parallel
  {
    std::vector<int> cand;
    std::vector<double> dist;
#pragma omp for schedule(dynamic, 16)
    for (int i = 0; i < leaves; ++i)
      if (tree.leafSampleCount(i) > 0) leafSpacings<Dim>(tree, frameY, i, k, radius_, cand, dist);
  }
  for (double& r : radius_) r *= factor;
  const auto& nodes = tree.nodes();
  nodeRadius_.assign(nodes.size(), 0.0);
  for (std::size_t id = 0; id < nodes.size(); ++id)
    for (int j = nodes[id].begin; j < nodes[id].end; ++j)
      nodeRadius_[id] = std::max(nodeRadius_[id], radius_[static_cast<std::size_t>(j)]);
}

template <int Dim>
bool PuDataReach<Dim>::reaches(const PuTree<Dim>& tree, const Vec<Dim>& y) const {
  if (radius_.empty()) return true;
  const auto& nodes = tree.nodes();
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int id = stack[--top];
    const auto& nd = nodes[static_cast<std::size_t>(id)];
    const double r = nodeRadius_[static_cast<std::size_t>(id)];
    if (nd.begin == nd.end || nd.box.distanceTo(y) > r) continue;
    if (nd.firstChild >= 0) {
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
      continue;
    }
    for (int j = nd.begin; j < nd.end; ++j) {
      const double rj = radius_[static_cast<std::size_t>(j)];
      if ((points_.col(j) - y).squaredNorm() <= rj * rj) return true;
    }
  }
  return false;
}

template class PuDataReach<2>;
template class PuDataReach<3>;

}  // namespace hermite
