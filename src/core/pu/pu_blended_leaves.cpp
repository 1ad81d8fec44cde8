#include "core/pu/pu_blended_leaves.h"

#include <cmath>

namespace hermite::detail {

namespace {

// Whether blendedLeaves blends the empty leaf i (pu_blended_leaves.h).
template <int Dim>
bool blendedEmptyLeaf(const PuTree<Dim>& tree, int i, double overlap) {
  const auto& nodes = tree.nodes();
  const Box<Dim>& b = tree.leafBox(i);
  // A relative 1e-9 for rounding (edges are powers-of-two fractions of the root's).
  const double edge = (1.0 - 1e-9) * b.extent().maxCoeff();
  bool near = false;
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0 && !near) {
    const auto& nd = nodes[stack[--top]];
    if (nd.begin == nd.end || !boxesIntersect<Dim>(nd.box, b)) continue;
    if (nd.firstChild >= 0) {
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
    } else {
      near = 2.0 * nd.box.extent().maxCoeff() >= edge;
    }
  }
  return near && tree.countInBox(scaledBox<Dim>(b, overlap), 1, tree.leaves()[static_cast<std::size_t>(i)]) >= 1;
}

// Squared distance between two boxes (0 when they meet).
template <int Dim>
double squaredBoxDistance(const Box<Dim>& a, const Box<Dim>& b) {
  return (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(Vec<Dim>::Zero()).squaredNorm();
}

// Whether some sample pᵢ reaching the box b of tree node `node` (‖b − pᵢ‖ ≤ rᵢ) passes accept(j),
// j its position in tree.order(): a walk of the tree that skips nodes whose largest reach cannot
// meet b. It starts at the nearest ancestor holding b grown by the largest reach (every sample
// that reaches b lies in it; the margin covers the rounding of the distances).
template <int Dim, class Accept>
bool someSampleReaches(const PuTree<Dim>& tree, const PuDataReach<Dim>& reach, int node, const Accept& accept) {
  const auto& nodes = tree.nodes();
  const Box<Dim>& b = nodes[static_cast<std::size_t>(node)].box;
  const double grow = (1.0 + 1e-6) * reach.maxRadius();
  const Box<Dim> grown{b.lo.array() - grow, b.hi.array() + grow};
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = tree.enclosingNode(grown, node);
  while (top > 0) {
    const int id = stack[--top];
    const auto& nd = nodes[static_cast<std::size_t>(id)];
    if (nd.begin == nd.end ||
        normExceeds(squaredBoxDistance<Dim>(nd.box, b), reach.nodeRadius(static_cast<std::size_t>(id))))
      continue;
    if (nd.firstChild >= 0) {
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
      continue;
    }
    for (int j = nd.begin; j < nd.end; ++j)  // accept first: it is cheaper, and often false
      if (accept(j) && !normExceeds(squaredDistanceTo<Dim>(b, tree.sortedPoints().col(j)), reach.radiusAt(j)))
        return true;
  }
  return false;
}

// Empty leaves that some sample reaches (‖b − pᵢ‖ ≤ rᵢ: blendReachCover would blend them as
// cover boxes) while their longest edge exceeds kCoverEdge·rᵢ. A cover box fits its nearest few
// samples and alone decides f over the part of its box no other support reaches, so a box many
// reaches wide extrapolates those few samples into a stray sheet beside the surface (200 000
// armadillo samples: pieces of 23 and 19 triangles from a box 35 reaches wide).
constexpr double kCoverEdge = 2.0;

// Only leaves whose node id is at least `firstNode` are tested: a leaf that passed once passes
// again (its box, the samples and their reach stay), so later passes test only the new children.
template <int Dim>
std::vector<int> oversizedCoverLeaves(const PuTree<Dim>& tree, const PuDataReach<Dim>& reach,
                                      const std::vector<char>& nodeBlended, std::size_t firstNode) {
  const int n = tree.leafCount();
  std::vector<char> split(static_cast<std::size_t>(n), 0);
#pragma omp parallel for schedule(dynamic, 64)
  for (int i = 0; i < n; ++i) {
    const auto node = static_cast<std::size_t>(tree.leaves()[static_cast<std::size_t>(i)]);
    if (node < firstNode || tree.leafSampleCount(i) > 0 || (node < nodeBlended.size() && nodeBlended[node])) continue;
    const double edge = tree.leafBox(i).extent().maxCoeff();
    const bool coarse = someSampleReaches(tree, reach, static_cast<int>(node),
                                          [&](int j) { return edge > kCoverEdge * reach.radiusAt(j); });
    split[static_cast<std::size_t>(i)] = coarse ? 1 : 0;
  }
  std::vector<int> out;
  for (int i = 0; i < n; ++i)
    if (split[static_cast<std::size_t>(i)]) out.push_back(i);
  return out;
}

}  // namespace

template <int Dim>
std::vector<char> blendedLeaves(const PuTree<Dim>& tree, PuBlend blend, double overlap) {
  const int n = tree.leafCount();
  std::vector<char> out(static_cast<std::size_t>(n), 1);
  if (blend == PuBlend::Hard) return out;
#pragma omp parallel for schedule(dynamic, 64)
  for (int i = 0; i < n; ++i)
    if (tree.leafSampleCount(i) == 0) out[static_cast<std::size_t>(i)] = blendedEmptyLeaf<Dim>(tree, i, overlap);
  return out;
}

// A blended empty box may be twice as wide as the data box it touches, itself many spacings wide
// where few samples fall in it (a box that clips a face's corner). Beside a large face parallel to
// one of its sides, its support reaches the face at one L∞ distance: shrinking it to hold
// limits.max samples (initialFactor) either keeps the whole square of the face it meets or nothing,
// and its local fit takes hundreds of samples at (4k + 4)³/3 flops. Such boxes are split (into
// empty children, classified afresh by blendedEmptyLeaf) until none is left; children reach the
// face from closer, by a smaller square. Boxes whose support at the overlap holds at most
// limits.max are not tested: they keep it, or grow to reach limits.min. Smooth blend only.
template <int Dim>
void splitCrowdedBlended(PuTree<Dim>& tree, std::vector<char>& blended, const PuOptions& options,
                         const LeafFitter<Dim>& fitter, const SupportLimits& limits) {
  if (options.blend != PuBlend::Smooth) return;
  std::vector<char> byNode(tree.nodes().size(), 0);  // blended, by node id (ids survive splits)
  for (int i = 0; i < tree.leafCount(); ++i)
    byNode[static_cast<std::size_t>(tree.leaves()[static_cast<std::size_t>(i)])] = blended[static_cast<std::size_t>(i)];
  std::size_t firstNode = 0;  // a leaf tested once keeps its answer: later passes test the new ones
  for (int pass = 0; pass < 32; ++pass) {
    throwIfCancelled(fitter.cancel());
    const int n = tree.leafCount();
    std::vector<char> crowded(static_cast<std::size_t>(n), 0);
#pragma omp parallel
    {
      LeafScratch<Dim> scratch;
#pragma omp for schedule(dynamic, 64)
      for (int i = 0; i < n; ++i) {
        const auto node = static_cast<std::size_t>(tree.leaves()[static_cast<std::size_t>(i)]);
        if (node < firstNode || !byNode[node] || tree.leafSampleCount(i) > 0) continue;
        // Cheap first: a support at the overlap holding at most limits.max samples stays, or grows
        // to its nearest limits.min (more only where many lie at one distance: a few boxes).
        const Box<Dim> support = scaledBox<Dim>(tree.leafBox(i), options.overlap);
        if (tree.countInBox(support, limits.max, static_cast<int>(node)) <= limits.max) continue;
        crowded[static_cast<std::size_t>(i)] = fitter.supportSamples(i, scratch) > limits.max ? 1 : 0;
      }
    }
    std::vector<int> split;
    for (int i = 0; i < n; ++i)
      if (crowded[static_cast<std::size_t>(i)]) split.push_back(i);
    firstNode = tree.nodes().size();
    if (!split.empty()) tree.splitEmptyLeaves(split);
    if (tree.leafCount() == n) break;  // none crowded, or every one at the tree's depth limit
    byNode.resize(tree.nodes().size(), 0);
    const int m = tree.leafCount();
#pragma omp parallel for schedule(dynamic, 64)
    for (int i = 0; i < m; ++i) {
      const auto node = static_cast<std::size_t>(tree.leaves()[static_cast<std::size_t>(i)]);
      if (node >= firstNode) byNode[node] = blendedEmptyLeaf<Dim>(tree, i, options.overlap);
    }
  }
  blended.resize(static_cast<std::size_t>(tree.leafCount()));
  for (int i = 0; i < tree.leafCount(); ++i)
    blended[static_cast<std::size_t>(i)] = byNode[static_cast<std::size_t>(tree.leaves()[static_cast<std::size_t>(i)])];
}

// The data reach is covered by blended boxes (docs/maths.md, "No data"): an empty leaf whose box
// comes within rᵢ of a sample pᵢ is blended too, so S > 0 — f has a value, not the no-data jump —
// wherever valid() can hold. Not 2·rᵢ: the mesher's widened reach dₖ + δ (PuDataReach::reaches,
// δ a cell diagonal) exceeds rᵢ only on grids coarser than the spacing, and there the supports
// of the data boxes and their blended neighbours, about a box past the data, already give S > 0
// (meshes close up to δ ≈ 7·dₖ: 20 000 sphere samples at 16³); a doubled cover would blend and
// fit a band of empty boxes twice as thick around every surface, for every fit.
template <int Dim>
void blendReachCover(const PuTree<Dim>& tree, const PuDataReach<Dim>& reach, std::vector<char>& blended) {
  if (reach.empty()) return;
  const int n = tree.leafCount();
#pragma omp parallel for schedule(dynamic, 64)
  for (int i = 0; i < n; ++i) {
    if (blended[static_cast<std::size_t>(i)]) continue;
    if (someSampleReaches(tree, reach, tree.leaves()[static_cast<std::size_t>(i)], [](int) { return true; }))
      blended[static_cast<std::size_t>(i)] = kCover;
  }
}

// Splits the empty leaves within reach of the data that the smooth blend does not already fit
// on their own supports (`blended`, per leaf of the tree as built) until none is wider than
// kCoverEdge reaches of a sample reaching it (each pass halves them). `reach` stays valid for the
// final tree: the splits add only empty nodes (radius 0) and keep the samples' order. `blended`
// is carried over to its leaves (the new ones are not blended: at most cover boxes,
// blendReachCover).
template <int Dim>
void refineCover(PuTree<Dim>& tree, const PuDataReach<Dim>& reach, std::vector<char>& blended,
                 const CancelToken* cancel) {
  std::vector<char> nodeBlended(tree.nodes().size(), 0);  // node ids survive splits; new nodes are not blended
  for (int i = 0; i < tree.leafCount(); ++i)
    nodeBlended[static_cast<std::size_t>(tree.leaves()[static_cast<std::size_t>(i)])] = blended[static_cast<std::size_t>(i)];
  bool changed = false;
  std::size_t firstNode = 0;  // the first pass tests every leaf, later ones the new children
  for (int pass = 0; pass < 32; ++pass) {
    throwIfCancelled(cancel);
    const std::vector<int> coarse = oversizedCoverLeaves<Dim>(tree, reach, nodeBlended, firstNode);
    const int before = tree.leafCount();
    firstNode = tree.nodes().size();
    if (!coarse.empty()) tree.splitEmptyLeaves(coarse);
    if (tree.leafCount() == before) break;
    changed = true;
  }
  if (!changed) return;
  blended.assign(static_cast<std::size_t>(tree.leafCount()), 0);
  for (int i = 0; i < tree.leafCount(); ++i) {
    const auto node = static_cast<std::size_t>(tree.leaves()[static_cast<std::size_t>(i)]);
    if (node < nodeBlended.size()) blended[static_cast<std::size_t>(i)] = nodeBlended[node];
  }
}

template std::vector<char> blendedLeaves<2>(const PuTree<2>&, PuBlend, double);
template std::vector<char> blendedLeaves<3>(const PuTree<3>&, PuBlend, double);
template void splitCrowdedBlended<2>(PuTree<2>&, std::vector<char>&, const PuOptions&, const LeafFitter<2>&,
                                     const SupportLimits&);
template void splitCrowdedBlended<3>(PuTree<3>&, std::vector<char>&, const PuOptions&, const LeafFitter<3>&,
                                     const SupportLimits&);
template void refineCover<2>(PuTree<2>&, const PuDataReach<2>&, std::vector<char>&, const CancelToken*);
template void refineCover<3>(PuTree<3>&, const PuDataReach<3>&, std::vector<char>&, const CancelToken*);
template void blendReachCover<2>(const PuTree<2>&, const PuDataReach<2>&, std::vector<char>&);
template void blendReachCover<3>(const PuTree<3>&, const PuDataReach<3>&, std::vector<char>&);

}  // namespace hermite::detail
