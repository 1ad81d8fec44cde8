#include "core/pu/pu_model.h"

#include <algorithm>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <map>
#include <mutex>

#include <omp.h>

#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "core/base/memory_check.h"
#include "core/base/threading.h"
#include "core/pu/pu_local_fit.h"
#include "core/pu/pu_near_field.h"
#include "core/rbf/dense_fit_memory.h"
#include "core/rbf/dense_solver.h"

namespace hermite {

namespace {

// max over t ∈ [−1, 1] of |d/dt (1 − t²)³| = |6t(1 − t²)²|, reached at t = 1/√5.
constexpr double kMaxBumpSlope = 6.0 / 2.2360679774997896964 * 0.64;

bool isIdentity(const Similarity<2>& T) {
  return T.q == 1.0 && T.t.isZero(0.0) && T.R == Mat<2>::Identity();
}
bool isIdentity(const Similarity<3>& T) {
  return T.q == 1.0 && T.t.isZero(0.0) && T.R == Mat<3>::Identity();
}

// The median longest edge of the blended leaves' supports (frame units); 0 when none is blended.
template <class Leaf>
double medianSupportEdge(const std::vector<Leaf>& leaves) {
  std::vector<double> edges;
  for (const Leaf& l : leaves)
    if (l.blended) edges.push_back(l.support.extent().maxCoeff());
  if (edges.empty()) return 0.0;
  std::nth_element(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(edges.size() / 2), edges.end());
  return edges[edges.size() / 2];
}

// The C² bump of one support at y, with ∇ and Hessian in y coordinates when asked; axes in
// `frozen` (y clamped there) have zero derivatives. Returns 0 outside the support.
template <int Dim>
double bump(const Box<Dim>& support, const Vec<Dim>& y, const bool* frozen, Vec<Dim>* g, Mat<Dim>* H) {
  double b[Dim], db[Dim], d2b[Dim];
  for (int k = 0; k < Dim; ++k) {
    const double h = 0.5 * (support.hi(k) - support.lo(k));
    const double t = (y(k) - 0.5 * (support.hi(k) + support.lo(k))) / h;
    const double u = 1.0 - t * t;
    if (!(u > 0)) return 0.0;
    b[k] = u * u * u;
    db[k] = frozen[k] ? 0.0 : -6.0 * t * u * u / h;
    d2b[k] = frozen[k] ? 0.0 : u * (30.0 * t * t - 6.0) / (h * h);
  }
  double w = 1.0;
  for (int k = 0; k < Dim; ++k) w *= b[k];
  if (g) {
    for (int k = 0; k < Dim; ++k) {
      double p = db[k];
      for (int j = 0; j < Dim; ++j)
        if (j != k) p *= b[j];
      (*g)(k) = p;
    }
  }
  if (H) {
    for (int k = 0; k < Dim; ++k)
      for (int l = 0; l < Dim; ++l) {
        double p = (k == l) ? d2b[k] : db[k] * db[l];
        for (int j = 0; j < Dim; ++j)
          if (j != k && j != l) p *= b[j];
        (*H)(k, l) = p;
      }
  }
  return w;
}

// How many samples a local fit's support holds: at least `min` (enough for the polynomial, and
// several even for an empty box), at most `max` (beyond it the tree splits, or the support shrinks).
struct SupportLimits {
  int min = 1, max = 1;
};

template <int Dim>
SupportLimits supportLimits(const PuOptions& options) {
  const int m = monomialCount<Dim>(options.local.polynomial);
  SupportLimits limits;
  limits.min = options.minSamples > 0 ? options.minSamples
                                      : std::max({1, m, std::min(options.maxPointsPerBox, 2 * (Dim + 1))});
  // A local solve costs O(samples³): with 6·maxPointsPerBox the 2.5 % of fits above 3· did 60 % of
  // the factorisation work of 200 000 points sampled on a scan. 2· cut that further but gave a
  // 45° wedge a stray piece 4.7 % of its diagonal away (smaller supports beside a sharp edge
  // extrapolate past it); 3· keeps the wedge closed (docs/performance.md, Real data).
  // 3·maxPointsPerBox in 64 bits, saturated: a limit beyond INT_MAX means "no limit" (a huge
  // max_points_per_box would otherwise wrap to a negative limit and split everything).
  const std::int64_t automatic = std::min<std::int64_t>(3 * std::int64_t(options.maxPointsPerBox), INT_MAX);
  limits.max = std::max(limits.min, options.maxSupportSamples > 0 ? options.maxSupportSamples : int(automatic));
  return limits;
}

// blended[i] of an empty leaf blended only to cover the data reach (blendReachCover): its
// support, capped at the support-sample limit, may shrink to just beyond the box (no floor), so
// a box beside dense data (or larger than the data's boxes) neither fits thousands of samples
// nor reaches far over the surface.
constexpr char kCover = 2;

// A box's support that ends just short of a sharp edge, or of the far side of a part thinner
// than the support, holds the samples of one face only: its fit carries that face on past the
// edge, where the box still weighs, and the blend bulges there (docs/maths.md, "Samples across an
// edge"). So the fit of a box holding samples whose normals spread beyond kEdgeSpreadCos of their
// mean is checked against the samples in a shell beyond its support (a quarter of the box's
// longest edge per side, edgeShell): those whose normal makes more than kEdgeAngleCos with the
// fit's gradient, at a place where the box weighs at least kEdgeWeight a spacing inside its
// support, join its samples and the box is fitted once more. Smooth blend only (the hard blend
// uses each fit in its box).
constexpr double kEdgeShell = 0.5;
constexpr double kEdgeSpreadCos = 0.866;  // 30°: boxes on smooth parts are not checked
constexpr double kEdgeAngleCos = 0.7;     // 46°
constexpr double kEdgeWeight = 0.2;       // of the bump's peak 1
// At most this share of the support-sample limit joins a refit (checkLocalFitMemory counts it).
constexpr double kEdgeAddedShare = 0.5;
// A cover box whose nearest limits.min samples spread beyond kEdgeSpreadCos lies beside a crease:
// so few samples of two faces fit a surface that bends between them, off both where the box weighs
// (docs/maths.md, "Samples across an edge"). It fits this many times limits.min instead.
constexpr double kCoverCreaseShare = 2.0;

// Per-thread scratch of the local fits, reused from box to box.
template <int Dim>
struct LeafScratch {
  int node = 0;              // the leaf's tree node (where the support queries start)
  std::vector<int> shell;    // samples of the shell beyond the support (refitAcrossEdges)
  std::vector<int> pos;      // the support's samples, as positions in the tree's order
  std::vector<int> idx;      // the same samples' indices, ascending (the local fit's order)
  std::vector<double> dist;  // their reach (the support factor that just holds each)
  HermiteSamples<Dim> sub;   // the local fit's data
};

// The local fit of each leaf box: chooses its support (scaled box) and fits the samples in it,
// growing the support while the local system is singular.
template <int Dim>
class LeafFitter {
 public:
  using Leaf = typename PuModel<Dim>::Leaf;

  // `reach`: the samples' data reach (their spacings), or null for the hard blend (no edge check).
  LeafFitter(const HermiteSamples<Dim>& samples, const PuTree<Dim>& tree, const PuOptions& options,
             const HrbfOptions& local, SupportLimits limits, const std::vector<char>& kind,
             const PuDataReach<Dim>* reach)
      : samples_(samples), tree_(tree), options_(options), local_(local), limits_(limits), kind_(kind),
        reach_(reach) {}

  const CancelToken* cancel() const { return local_.cancel; }
  // The samples the support of blended leaf i would hold before its fit (initialFactor; a box
  // holding samples or a blended empty one, not a cover box).
  int supportSamples(int i, LeafScratch<Dim>& scratch) const {
    scratch.node = tree_.leaves()[static_cast<std::size_t>(i)];
    initialFactor(tree_.leafBox(i), supportFloor(), scratch);
    return static_cast<int>(scratch.pos.size());
  }
  // Fits leaf i; throws NumericalError when its system stays singular after growing.
  void fit(int i, Leaf& leaf, FitReport& report, LeafScratch<Dim>& scratch) const {
    const Box<Dim>& box = tree_.leafBox(i);
    scratch.node = tree_.leaves()[static_cast<std::size_t>(i)];
    const int n = samples_.size();
    const auto unblend = [&] {  // no data there: no fit, its nominal support for display
      leaf.blended = false;
      leaf.support = scaledBox<Dim>(box, options_.overlap);
      leaf.factor = options_.overlap;
      leaf.samples = 0;
    };
    if (!leaf.blended) return unblend();
    std::vector<int>& pos = scratch.pos;
    const bool cover = kind_[static_cast<std::size_t>(i)] == kCover;
    double s = cover ? coverSupport(box, scratch) : initialFactor(box, supportFloor(), scratch);
    // A cover box whose support cannot stay small (samples at one L∞ distance: a box off a flat
    // cloud reaches a whole square of it) or whose fit fails is left out, not grown: it only widens
    // where f has a value.
    if (cover && static_cast<int>(pos.size()) > 4 * std::min(limits_.min, n)) return unblend();
    // A singular local system (e.g. collinear samples under a quadratic term) grows too.
    for (int attempt = 0;; ++attempt) {
      gatherPositions(scratch);
      const int k = static_cast<int>(pos.size());
      try {
        leaf.model = fitPuLocal<Dim>(scratch.sub, local_, report);
        leaf.support = scaledBox<Dim>(box, s);
        leaf.factor = s;
        leaf.samples = k;
        if (!cover && reach_) refitAcrossEdges(box, leaf, report, scratch);
        return;
      } catch (const NumericalError& e) {
        if (cover) return unblend();
        if (attempt >= 4 || k >= n)
          throw NumericalError("partition: local fit of box " + std::to_string(i) + " (" + std::to_string(k) +
                               " samples) failed: " + e.what());
        s *= options_.growth;
        tree_.positionsInBox(scaledBox<Dim>(box, s), pos, scratch.node);
        report = FitReport{};
      }
    }
  }

 private:
  // The least support factor of a box that is not a cover box: halfway between the box and the overlap.
  double supportFloor() const { return 0.5 * (1.0 + options_.overlap); }

  // The support factor of a box, its samples in scratch.pos: the overlap, grown just enough for
  // the support to hold limits.min samples, or shrunk (not below the floor) to hold at most limits.max.
  double initialFactor(const Box<Dim>& box, double floor, LeafScratch<Dim>& scratch) const {
    std::vector<int>& pos = scratch.pos;
    double s = options_.overlap;
    tree_.positionsInBox(scaledBox<Dim>(box, s), pos, scratch.node);
    const int want = std::min(limits_.min, samples_.size());
    if (static_cast<int>(pos.size()) < want) {
      s = nearestSupport(box, want, s, scratch);
    } else if (static_cast<int>(pos.size()) > limits_.max) {
      s = factorReaching(box, limits_.max, floor, scratch);
      narrowSamples(scaledBox<Dim>(box, options_.overlap), scaledBox<Dim>(box, s), scratch);
    }
    return s;
  }

  // The support factor of a cover box, its samples in scratch.pos: its nearest limits.min samples
  // (the fewest a local fit takes: it only has to give f a value there), more beside a crease
  // (widenCover). The support at the overlap stays when it holds just that many.
  double coverSupport(const Box<Dim>& box, LeafScratch<Dim>& scratch) const {
    const int want = std::min(limits_.min, samples_.size());
    const bool more = tree_.countInBox(scaledBox<Dim>(box, options_.overlap), want, scratch.node) > want;
    const double s = nearestSupport(box, want, more ? 1.0 : options_.overlap, scratch);
    return normalsSpread(scratch.pos) ? widenCover(box, s, scratch) : s;
  }

  // The support factor of a cover box beside a crease (kCoverCreaseShare, above), from its factor
  // `s` holding its nearest limits.min samples (scratch.pos): grown just enough to hold
  // kCoverCreaseShare times as many (at most limits.max); scratch.pos ← its samples.
  double widenCover(const Box<Dim>& box, double s, LeafScratch<Dim>& scratch) const {
    const int want = std::min(static_cast<int>(std::ceil(kCoverCreaseShare * limits_.min)), limits_.max);
    if (want > samples_.size() || static_cast<int>(scratch.pos.size()) >= want) return s;
    return nearestSupport(box, want, s, scratch);
  }

  // The support factor just reaching the `want`-th nearest sample (≤ the sample count), but at
  // least `floor`; scratch.pos ← the samples it holds. One nearest-first walk of the tree and one
  // query of that support (not walks of supports grown step by step until they hold enough).
  double nearestSupport(const Box<Dim>& box, int want, double floor, LeafScratch<Dim>& scratch) const {
    const double s = reachingFactor(tree_.kthScaledDistance(box, want), floor);
    tree_.positionsInBox(scaledBox<Dim>(box, s), scratch.pos, scratch.node);
    return s;
  }

  // The support factor holding a sample at scaled L∞ distance d, but at least `floor`: a relative
  // 1e-9 beyond the sample, so rounding of the scaled box cannot drop it (its weight there, ~1e-26,
  // is negligible).
  static double reachingFactor(double d, double floor) { return std::max(floor, d * (1.0 + 1e-9)); }

  // The edge check above kEdgeShell (scratch.pos: the fitted samples): adds the disagreeing shell
  // samples to scratch.pos and fits again; a refit that fails keeps the first fit.
  void refitAcrossEdges(const Box<Dim>& box, Leaf& leaf, FitReport& report, LeafScratch<Dim>& scratch) const {
    std::vector<int>& pos = scratch.pos;
    if (!normalsSpread(pos)) return;
    tree_.positionsInBox(edgeShell(box, leaf.support), scratch.shell, scratch.node);
    const std::size_t fitted = pos.size(), most = fitted + static_cast<std::size_t>(kEdgeAddedShare * limits_.max);
    for (int j : scratch.shell)
      if (pos.size() < most && !leaf.support.contains(tree_.sortedPoints().col(j)) && disagrees(leaf, j))
        pos.push_back(j);
    if (pos.size() == fitted) return;
    gatherPositions(scratch);
    FitReport again;
    try {
      leaf.model = fitPuLocal<Dim>(scratch.sub, local_, again);
    } catch (const NumericalError&) {
      return;  // the first fit stays (fitPuLocal threw before assigning)
    }
    report = std::move(again);
    leaf.samples = static_cast<int>(pos.size());
  }

  // The support grown by ½·kEdgeShell of the box's longest edge on every side: a box thin along an
  // axis looks as far beyond its support along it as along the others.
  static Box<Dim> edgeShell(const Box<Dim>& box, const Box<Dim>& support) {
    const Vec<Dim> pad = Vec<Dim>::Constant(0.5 * kEdgeShell * box.extent().maxCoeff());
    return Box<Dim>{support.lo - pad, support.hi + pad};
  }

  // Whether the normals of the samples at positions `pos` spread beyond kEdgeSpreadCos of their mean.
  bool normalsSpread(const std::vector<int>& pos) const {
    const auto normal = [&](int j) { return samples_.normals.col(tree_.order()[static_cast<std::size_t>(j)]); };
    Vec<Dim> mean = Vec<Dim>::Zero();
    for (int j : pos) mean += normal(j);
    mean.normalize();
    for (int j : pos)
      if (!(mean.dot(normal(j)) >= kEdgeSpreadCos)) return true;
    return false;
  }

  // Whether the shell sample at position j (outside the leaf's support) has a normal more than
  // kEdgeAngleCos from the leaf's fit's gradient, and the box weighs at least kEdgeWeight a spacing
  // (dₖ, its data reach over c) inside the support from it.
  bool disagrees(const Leaf& leaf, int j) const {
    const Box<Dim>& support = leaf.support;
    const Vec<Dim> y = tree_.sortedPoints().col(j);
    Vec<Dim> inside = y.cwiseMax(support.lo).cwiseMin(support.hi);
    const Vec<Dim> toCentre = support.center() - inside;
    const double spacing = reach_->radiusAt(j) / reach_->factor();
    if (toCentre.norm() > 0) inside += std::min(spacing, toCentre.norm()) * toCentre.normalized();
    const bool frozen[Dim] = {};
    if (bump<Dim>(support, inside, frozen, nullptr, nullptr) < kEdgeWeight) return false;
    const int i = tree_.order()[static_cast<std::size_t>(j)];
    Vec<Dim> g;
    leaf.model.evaluate(samples_.points.col(i), &g);
    return g.dot(samples_.normals.col(i)) < kEdgeAngleCos * g.norm();
  }

  // scratch.pos ← the samples `query` holds, given those `previous` holds. When query lies inside
  // previous this keeps the entries query contains — the set positionsInBox returns (a box holds
  // exactly the samples it contains), in another order (the fit sorts the indices) — without a
  // walk of the tree; otherwise it walks the tree.
  void narrowSamples(const Box<Dim>& previous, const Box<Dim>& query, LeafScratch<Dim>& scratch) const {
    std::vector<int>& pos = scratch.pos;
    const bool inside =
        (query.lo.array() >= previous.lo.array()).all() && (query.hi.array() <= previous.hi.array()).all();
    if (!inside) return tree_.positionsInBox(query, pos, scratch.node);
    const Points<Dim>& Y = tree_.sortedPoints();
    pos.erase(std::remove_if(pos.begin(), pos.end(), [&](int j) { return !query.contains(Y.col(j)); }), pos.end());
  }

  // scratch.sub ← the samples at the positions scratch.pos, by ascending sample index (scratch.idx):
  // the local fit's data in the order of the samples, whatever the order of the tree walk.
  void gatherPositions(LeafScratch<Dim>& scratch) const {
    const std::vector<int>& pos = scratch.pos;
    std::vector<int>& idx = scratch.idx;
    idx.resize(pos.size());
    for (std::size_t j = 0; j < pos.size(); ++j) idx[j] = tree_.order()[static_cast<std::size_t>(pos[j])];
    std::sort(idx.begin(), idx.end());
    gatherSamples(idx, scratch.sub);
  }

  // The support factor just large enough for the `rank`-th nearest of the samples in
  // scratch.pos (normalised L∞ distance about the box centre), but at least `floor`.
  double factorReaching(const Box<Dim>& box, int rank, double floor, LeafScratch<Dim>& scratch) const {
    const Vec<Dim> c = box.center();
    const Vec<Dim> invH = (0.5 * box.extent()).cwiseInverse();
    std::vector<double>& dist = scratch.dist;
    const Points<Dim>& Y = tree_.sortedPoints();
    dist.resize(scratch.pos.size());
    for (std::size_t j = 0; j < scratch.pos.size(); ++j)
      dist[j] = ((Y.col(scratch.pos[j]) - c).cwiseAbs().cwiseProduct(invH)).maxCoeff();
    std::nth_element(dist.begin(), dist.begin() + (rank - 1), dist.end());
    return reachingFactor(dist[rank - 1], floor);
  }

  // The samples idx (points and normals, in that order) as the local fit's data.
  void gatherSamples(const std::vector<int>& idx, HermiteSamples<Dim>& sub) const {
    const int k = static_cast<int>(idx.size());
    sub.points.resize(Dim, k);
    sub.normals.resize(Dim, k);
    for (int j = 0; j < k; ++j) {
      sub.points.col(j) = samples_.points.col(idx[j]);
      sub.normals.col(j) = samples_.normals.col(idx[j]);
    }
  }

  const HermiteSamples<Dim>& samples_;
  const PuTree<Dim>& tree_;
  const PuOptions& options_;
  const HrbfOptions& local_;
  SupportLimits limits_;
  const std::vector<char>& kind_;  // per leaf: 0 not blended, 1 blended, kCover
  const PuDataReach<Dim>* reach_;
};

// Which leaves the blend uses (docs/maths.md, "No data"). Smooth blend: the boxes holding
// samples, and the empty boxes touching one of them that are at most twice its longest edge and
// whose support at `overlap` holds a sample (a support that must grow to reach any sample would
// fit distant ones, e.g. across the thin boxes of a flat cloud) —
// a margin of about one box beyond the data, so the cells of a coarser mesh across the surface
// still have data at every corner, without the far extrapolations of big empty boxes. Each is
// fitted on its own support (borrowing a neighbour's fit instead extrapolates that fit a whole box
// and grows sheets). Hard blend: every leaf. blendedEmptyLeaf answers for one empty leaf.
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

// Refuses (MemoryLimitError) a PU fit whose local fits, one per thread at once, need more memory
// than is available: each holds a system of at most min(n, limits.max · (1 + kEdgeAddedShare))
// samples, as the in-process path (kernel block and saddle matrix: 2 square matrices) or
// fitHrbf's, plus each thread's BLAS buffer when the fits themselves reach kUncheckedBytes.
template <int Dim>
void checkLocalFitMemory(int samples, const SupportLimits& limits, const HrbfOptions& local) {
  const auto most = static_cast<std::int64_t>(limits.max) + static_cast<std::int64_t>(kEdgeAddedShare * limits.max);
  const std::int64_t k = std::min<std::int64_t>(samples, most);  // a refit across an edge adds to the limit
  const std::int64_t m = monomialCount<Dim>(local.polynomial);
  const std::int64_t unknowns = k * (Dim + 1) + m;
  const SolverChoice path =
      plannedSolverPath(local.solver, m, kernelDefiniteSign(local.kernel, local.polynomial, local.smoothing));
  const std::uint64_t perFit = std::max(denseFitBytes(unknowns, path, m),
                                        saturatingProduct({2, std::uint64_t(unknowns), std::uint64_t(unknowns), 8}));
  const int threads = omp_get_max_threads();
  const std::uint64_t fits = saturatingProduct({perFit, std::uint64_t(threads)});
  checkMemory({fits < kUncheckedBytes ? fits : saturatingSum({fits, blasBufferBytes(threads)}),
               "the partition-of-unity fit (" + std::to_string(threads) + " local fits at once, each of up to " +
                   std::to_string(unknowns) + " unknowns)"},
              "lower fit.partition.max_points_per_box or use fewer --threads");
}

// Fits every leaf, in parallel over boxes with one BLAS thread each (the local systems are
// small); rethrows the first failure after all threads are done. The cancel token is polled box
// by box (a box is milliseconds of work): once it is set the remaining boxes are skipped and
// Cancelled is rethrown.
template <int Dim>
void fitLeaves(const LeafFitter<Dim>& fitter, std::vector<typename PuModel<Dim>::Leaf>& leaves,
               std::vector<FitReport>& reports) {
  const int leafCount = static_cast<int>(leaves.size());
  std::exception_ptr failure;
  std::mutex failureMutex;
  const int blasThreads = blasThreadCount();
  setBlasThreadCount(1);
#pragma omp parallel
  {
    LeafScratch<Dim> scratch;
#pragma omp for schedule(dynamic, 8)
    for (int i = 0; i < leafCount; ++i) {
      try {
        throwIfCancelled(fitter.cancel());
        fitter.fit(i, leaves[i], reports[i], scratch);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failureMutex);
        if (!failure) failure = std::current_exception();
      }
    }
  }
  setBlasThreadCount(blasThreads);
  if (failure) std::rethrow_exception(failure);
}

// The local fits' warnings other than `skip`, grouped by kind (the text with its numbers
// blanked), as one line per kind: its count and its first example.
std::vector<std::string> groupLocalWarnings(const std::vector<FitReport>& reports,
                                            const std::vector<std::string>& skip) {
  std::vector<std::pair<std::string, std::pair<int, std::string>>> kinds;
  for (std::size_t i = 0; i < reports.size(); ++i) {
    for (const std::string& w : reports[i].warnings) {
      if (std::find(skip.begin(), skip.end(), w) != skip.end()) continue;
      std::string kind;
      for (char ch : w)
        if (!(ch >= '0' && ch <= '9') && ch != '.' && ch != '+' && ch != 'e') kind += ch;
      auto it = std::find_if(kinds.begin(), kinds.end(), [&](const auto& k) { return k.first == kind; });
      if (it == kinds.end())
        kinds.push_back({kind, {1, "box " + std::to_string(i) + ": " + w}});
      else
        ++it->second.first;
    }
  }
  std::vector<std::string> lines;
  for (const auto& [kind, info] : kinds)
    lines.push_back("partition: " + std::to_string(info.first) + " of " + std::to_string(reports.size()) +
                    " local fits warned like " + info.second);
  return lines;
}

// The fit's report from its tree and local fits (all but the timings).
template <int Dim>
PuReport summariseFits(const PuTree<Dim>& tree, const std::vector<typename PuModel<Dim>::Leaf>& leaves,
                       const std::vector<FitReport>& reports, const PuOptions& options, const HrbfOptions& local) {
  const int leafCount = static_cast<int>(leaves.size());
  PuReport r;
  r.boxes = leafCount;
  r.warnings = polynomialOrderWarnings(local.kernel, local.polynomial);
  std::map<std::string, int> solvers;
  for (int i = 0; i < leafCount; ++i) r.fittedBoxes += leaves[i].blended ? 1 : 0;
  int* same = nullptr;  // the count of the last solver name: neighbouring boxes mostly share it
  const std::string* last = nullptr;
  for (int i = 0; i < leafCount; ++i) {
    r.maxBoxSamples = std::max(r.maxBoxSamples, tree.leafSampleCount(i));
    if (!leaves[i].blended) continue;
    r.maxSupportSamples = std::max(r.maxSupportSamples, leaves[i].samples);
    r.meanSupportSamples += leaves[i].samples / double(r.fittedBoxes);
    if (leaves[i].factor > options.overlap) ++r.grownSupports;
    r.unknowns += reports[i].nUnknowns;
    r.maxConditionEstimate = std::max(r.maxConditionEstimate, reports[i].conditionEstimate);
    if (!last || *last != reports[i].solver) {
      last = &reports[i].solver;
      same = &solvers[*last];
    }
    ++*same;
  }
  int best = -1;
  for (const auto& [name, count] : solvers)
    if (count > best) {
      best = count;
      r.solver = name;
    }
  for (std::string& line : groupLocalWarnings(reports, r.warnings)) r.warnings.push_back(std::move(line));
  return r;
}

}  // namespace

template <int Dim>
Similarity<Dim> composeSimilarity(const Similarity<Dim>& S, const Similarity<Dim>& T) {
  Similarity<Dim> out;
  out.q = S.q * T.q;
  out.R = S.R * T.R;
  out.t = S.q * (S.R * T.t) + S.t;
  return out;
}

template <int Dim>
PuModel<Dim>::PuModel(PuTree<Dim> tree, std::vector<Leaf> leaves, const PuOptions& options,
                      const Similarity<Dim>& frame, PuDataReach<Dim> dataReach)
    : tree_(std::move(tree)),
      leaves_(std::move(leaves)),
      options_(options),
      frame_(frame),
      dataReach_(std::move(dataReach)) {
  identityFrame_ = isIdentity(frame_);
  minFactor_ = std::numeric_limits<double>::infinity();
  for (const Leaf& l : leaves_)
    if (l.blended) minFactor_ = std::min(minFactor_, l.factor);
  if (!std::isfinite(minFactor_)) minFactor_ = 1.0;
  noData_ = tree_.nodes().empty() ? 1.0 : frame_.q * tree_.root().extent().norm();
  typicalSupport_ = medianSupportEdge(leaves_);
  buildReach();
}

template <int Dim>
void PuModel<Dim>::buildReach() {
  const auto& nodes = tree_.nodes();
  reach_.assign(nodes.size(), Box<Dim>{});
  allBlended_.assign(nodes.size(), 1);
  // Children come after their parent: a backward pass sees them first.
  for (int id = static_cast<int>(nodes.size()) - 1; id >= 0; --id) {
    const auto& nd = nodes[id];
    if (nd.firstChild < 0) {
      if (leaves_[nd.leaf].blended) {
        reach_[id] = leaves_[nd.leaf].support;
      } else {  // never blended: an empty reach
        allBlended_[static_cast<std::size_t>(id)] = 0;
        reach_[id].lo.setConstant(std::numeric_limits<double>::infinity());
        reach_[id].hi.setConstant(-std::numeric_limits<double>::infinity());
      }
    } else {
      Box<Dim> r = reach_[nd.firstChild];
      for (int ch = 1; ch < PuTree<Dim>::kChildren; ++ch) {
        r.lo = r.lo.cwiseMin(reach_[nd.firstChild + ch].lo);
        r.hi = r.hi.cwiseMax(reach_[nd.firstChild + ch].hi);
      }
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch)
        if (!allBlended_[static_cast<std::size_t>(nd.firstChild + ch)]) allBlended_[static_cast<std::size_t>(id)] = 0;
      reach_[id] = r;
    }
  }
}

template <int Dim>
template <class Accept>
bool PuModel<Dim>::anySupportAt(const Vec<Dim>& y, Accept&& accept) const {
  const auto& nodes = tree_.nodes();
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int id = stack[--top];
    if (!reach_[id].contains(y)) continue;
    const auto& nd = nodes[id];
    if (nd.firstChild < 0) {
      if (accept(nd.leaf)) return true;
    } else {
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
    }
  }
  return false;
}

template <int Dim>
template <class F>
void PuModel<Dim>::forSupportsAt(const Vec<Dim>& y, F&& visit) const {
  anySupportAt(y, [&](int leaf) {
    visit(leaf);
    return false;  // every support
  });
}

template <int Dim>
template <class F>
void PuModel<Dim>::forSupportsTouching(const Box<Dim>& b, F&& visit) const {
  const auto& nodes = tree_.nodes();
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int id = stack[--top];
    if (!boxesIntersect<Dim>(reach_[id], b)) continue;
    const auto& nd = nodes[id];
    if (nd.firstChild < 0) {
      visit(nd.leaf);
    } else {
      for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
    }
  }
}

template <int Dim>
double PuModel<Dim>::evaluate(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H) const {
  return evaluateValid(x, g, H, nullptr);
}

template <int Dim>
double PuModel<Dim>::evaluateValid(const Vec<Dim>& x, Vec<Dim>* g, Mat<Dim>* H, bool* valid) const {
  if (valid) *valid = true;
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  if (options_.blend == PuBlend::Hard) return leaves_[tree_.locateLeaf(y)].model.evaluate(x, g, H);
  const bool frozen[Dim] = {};
  const Vec<Dim>& yc = y;
  const bool needG = g != nullptr || H != nullptr;
  const bool needH = H != nullptr;
  // f = N/S with N = Σ wᵢfᵢ, S = Σ wᵢ; derivatives of N and S by the product rule.
  double S = 0, N = 0;
  Vec<Dim> gS = Vec<Dim>::Zero(), gN = Vec<Dim>::Zero();
  Mat<Dim> HS = Mat<Dim>::Zero(), HN = Mat<Dim>::Zero();
  const double invQ = 1.0 / frame_.q;
  forSupportsAt(yc, [&](int i) {
    const Leaf& leaf = leaves_[i];
    if (!leaf.support.contains(yc)) return;
    Vec<Dim> gw;
    Mat<Dim> Hw;
    const double w = bump<Dim>(leaf.support, yc, frozen, needG ? &gw : nullptr, needH ? &Hw : nullptr);
    if (w == 0.0) return;
    if (!identityFrame_) {
      // y = R⁻¹(x − t)/q: ∇ₓ = R∇_y/q, Hₓ = R H_y Rᵀ/q².
      if (needG) gw = invQ * (frame_.R * gw);
      if (needH) Hw = (invQ * invQ) * (frame_.R * Hw * frame_.R.transpose());
    }
    Vec<Dim> gi;
    Mat<Dim> Hi;
    const double fi = leaf.model.evaluate(x, needG ? &gi : nullptr, needH ? &Hi : nullptr);
    S += w;
    N += w * fi;
    if (needG) {
      gS += gw;
      gN += fi * gw + w * gi;
    }
    if (needH) {
      HS += Hw;
      HN += fi * Hw + gw * gi.transpose() + gi * gw.transpose() + w * Hi;
    }
  });
  if (!(S > 0)) return evaluateUncovered(x, y, g, H, valid);
  if (valid) *valid = dataReach_.reaches(tree_, y);
  const double f = N / S;
  if (needG) {
    const Vec<Dim> gf = (gN - f * gS) / S;
    if (g) *g = gf;
    if (needH) *H = (HN - gf * gS.transpose() - gS * gf.transpose() - f * HS) / S;
  }
  return f;
}

template <int Dim>
double PuModel<Dim>::evaluateUncovered(const Vec<Dim>& x, const Vec<Dim>& y, Vec<Dim>* g, Mat<Dim>* H,
                                       bool* valid) const {
  if (tree_.root().contains(y)) {
    const Leaf& own = leaves_[tree_.locateLeaf(y)];
    if (own.blended) {
      if (valid) *valid = dataReach_.reaches(tree_, y);
      return own.model.evaluate(x, g, H);
    }
  }
  if (valid) *valid = false;
  if (g) g->setZero();
  if (H) H->setZero();
  return noData_;
}

template <int Dim>
bool PuModel<Dim>::valid(const Vec<Dim>& x) const {
  return validNear(x, 0.0);
}

template <int Dim>
bool PuModel<Dim>::validNear(const Vec<Dim>& x, double margin) const {
  if (options_.blend == PuBlend::Hard) return true;
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  const bool frozen[Dim] = {};
  const bool reached =
      anySupportAt(y, [&](int i) { return bump<Dim>(leaves_[i].support, y, frozen, nullptr, nullptr) > 0; });
  return (reached || (tree_.root().contains(y) && leaves_[tree_.locateLeaf(y)].blended)) &&
         dataReach_.reaches(tree_, y, margin / frame_.q);
}

template <int Dim>
bool PuModel<Dim>::validOnZeroSet(const Vec<Dim>& x) const {
  if (options_.blend == PuBlend::Hard || dataReach_.empty()) return valid(x);
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  const double scale = std::min(1.0, options_.vertexReach / dataReach_.factor());
  return dataReach_.reaches(tree_, y, 0.0, scale) && valid(x);
}

template <int Dim>
bool PuModel<Dim>::coveredByData(const Box<Dim>& yb) const {
  const Box<Dim>& root = tree_.root();
  if (!((yb.lo.array() >= root.lo.array()).all() && (yb.hi.array() <= root.hi.array()).all())) return false;
  const auto& nodes = tree_.nodes();
  int stack[64 * PuTree<Dim>::kChildren];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int id = stack[--top];
    const auto& nd = nodes[id];
    if (!boxesIntersect<Dim>(nd.box, yb) || allBlended_[static_cast<std::size_t>(id)]) continue;
    if (nd.firstChild < 0) return false;  // a leaf without data meets yb
    for (int ch = 0; ch < PuTree<Dim>::kChildren; ++ch) stack[top++] = nd.firstChild + ch;
  }
  return true;
}

// f (and ∇f) for the smooth blend by runs of kRun consecutive columns of X: callers that care pass
// neighbouring points next to each other (the mesher's blocks and vertices), so a run's bounding
// box meets few supports; a run of scattered points (scatteredRun) goes point by point. A run looks its supports up once and evaluates each local fit at the
// run's points inside its support by the fit's vectorised batch loop (nested in this parallel
// loop, it runs on the calling thread). Per point the sums are the ones evaluateValid() forms — the
// same supports in the same order (depth first, as forSupportsAt), N = Σ wᵢ fᵢ, S = Σ wᵢ and their
// gradients — with each fᵢ rounded as the vectorised loop rounds it, whatever the other columns.
template <int Dim>
struct PuRunScratch {
  // 32 points: fewer than 64 waste fewer support tests, more than 16 share the tree walk (mesh
  // of 200 000 and 1 000 000 points, docs/performance.md).
  static constexpr Eigen::Index kRun = 32;
  Vec<Dim> y[kRun], gS[kRun], gN[kRun], gw[kRun];
  double yAxis[Dim][kRun];  // the same y, one array per axis, for the containment test
  double S[kRun], N[kRun], w[kRun];
  int members[kRun], inside[kRun];
  std::vector<int> leaves;
  Points<Dim> Xi, Gi;
  Eigen::VectorXd fi;
};

namespace {

// sc.inside[0..k) ← the run's points (of `count`) that `box` contains, ascending; returns k. The
// same test as Box::contains, without a branch per point: a run meets 10–30 supports and holds
// 3–4 of their points on average, so a branch per point mispredicts on most of them.
template <int Dim>
int runPointsInside(const Box<Dim>& box, Eigen::Index count, PuRunScratch<Dim>& sc) {
  unsigned char in[PuRunScratch<Dim>::kRun];
  for (Eigen::Index j = 0; j < count; ++j) {
    bool c = true;
    for (int d = 0; d < Dim; ++d) c &= (sc.yAxis[d][j] >= box.lo[d]) & (sc.yAxis[d][j] <= box.hi[d]);
    in[j] = c;
  }
  int k = 0;
  for (Eigen::Index j = 0; j < count; ++j) {
    sc.inside[k] = static_cast<int>(j);
    k += in[j];
  }
  return k;
}

}  // namespace

template <int Dim>
void PuModel<Dim>::evaluateRun(const Points<Dim>& X, Eigen::Index begin, Eigen::Index count, Eigen::VectorXd& f,
                               Points<Dim>* G, PuRunScratch<Dim>& sc) const {
  const bool frozen[Dim] = {};
  const double invQ = 1.0 / frame_.q;
  Box<Dim> bb{Vec<Dim>::Constant(std::numeric_limits<double>::infinity()),
              Vec<Dim>::Constant(-std::numeric_limits<double>::infinity())};
  for (Eigen::Index j = 0; j < count; ++j) {
    sc.y[j] = identityFrame_ ? Vec<Dim>(X.col(begin + j)) : frame_.applyInverse(X.col(begin + j));
    for (int d = 0; d < Dim; ++d) sc.yAxis[d][j] = sc.y[j][d];
    bb.lo = bb.lo.cwiseMin(sc.y[j]);
    bb.hi = bb.hi.cwiseMax(sc.y[j]);
    sc.S[j] = sc.N[j] = 0;
    sc.gS[j].setZero();
    sc.gN[j].setZero();
  }
  sc.leaves.clear();
  forSupportsTouching(bb, [&](int i) { sc.leaves.push_back(i); });
  for (int i : sc.leaves) {
    const Leaf& leaf = leaves_[i];
    int m = 0;
    const int inside = runPointsInside<Dim>(leaf.support, count, sc);
    for (int c = 0; c < inside; ++c) {
      const int j = sc.inside[c];
      const double wj = bump<Dim>(leaf.support, sc.y[j], frozen, G ? &sc.gw[m] : nullptr, nullptr);
      if (wj == 0.0) continue;
      if (G && !identityFrame_) sc.gw[m] = invQ * (frame_.R * sc.gw[m]);
      sc.w[m] = wj;
      sc.members[m++] = j;
    }
    if (m == 0) continue;
    sc.Xi.resize(Dim, m);
    for (int k = 0; k < m; ++k) sc.Xi.col(k) = X.col(begin + sc.members[k]);
    leaf.model.evaluateBatch(sc.Xi, sc.fi, G ? &sc.Gi : nullptr);
    for (int k = 0; k < m; ++k) {
      const int j = sc.members[k];
      sc.S[j] += sc.w[k];
      sc.N[j] += sc.w[k] * sc.fi[k];
      if (G) {
        sc.gS[j] += sc.gw[k];
        sc.gN[j] += sc.fi[k] * sc.gw[k] + sc.w[k] * sc.Gi.col(k);
      }
    }
  }
  for (Eigen::Index j = 0; j < count; ++j) {
    Vec<Dim> g;
    if (!(sc.S[j] > 0)) {
      f(begin + j) = evaluateUncovered(X.col(begin + j), sc.y[j], G ? &g : nullptr, nullptr, nullptr);
    } else {
      f(begin + j) = sc.N[j] / sc.S[j];
      if (G) g = (sc.gN[j] - f(begin + j) * sc.gS[j]) / sc.S[j];
    }
    if (G) G->col(begin + j) = g;
  }
}

// A run whose points spread over more than kScatteredSupports typical supports across (along the
// second-longest axis of their box, in frame units) is scattered: its box meets a large part of the
// tree, and a walk per point costs less. Rows of a grid and the vertices of a mesh stay runs.
constexpr double kScatteredSupports = 4.0;

template <int Dim>
bool PuModel<Dim>::scatteredRun(const Points<Dim>& X, Eigen::Index begin, Eigen::Index count) const {
  if (count < 2) return false;
  Vec<Dim> lo = X.col(begin), hi = lo;
  for (Eigen::Index j = 1; j < count; ++j) {
    lo = lo.cwiseMin(X.col(begin + j));
    hi = hi.cwiseMax(X.col(begin + j));
  }
  Vec<Dim> extent = (hi - lo) / frame_.q;  // a rotation changes the axes, not much the spread
  std::sort(extent.data(), extent.data() + Dim);
  return extent[Dim - 2] > kScatteredSupports * typicalSupport_;
}

template <int Dim>
void PuModel<Dim>::evaluateBatch(const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>* G) const {
  const Eigen::Index n = X.cols();
  f.resize(n);
  if (G) G->resize(Dim, n);
  if (options_.blend == PuBlend::Smooth) {
    using Scratch = PuRunScratch<Dim>;
    const Eigen::Index runs = (n + Scratch::kRun - 1) / Scratch::kRun;
#pragma omp parallel
    {
      Scratch sc;
#pragma omp for schedule(dynamic, 4)
      for (Eigen::Index r = 0; r < runs; ++r) {
        const Eigen::Index begin = r * Scratch::kRun, count = std::min(Scratch::kRun, n - begin);
        if (!scatteredRun(X, begin, count)) {
          evaluateRun(X, begin, count, f, G, sc);
          continue;
        }
        for (Eigen::Index j = 0; j < count; ++j) evaluateRun(X, begin + j, 1, f, G, sc);
      }
    }
    return;
  }
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < n; ++i) {
    if (G) {
      Vec<Dim> g;
      f(i) = evaluate(X.col(i), &g);
      G->col(i) = g;
    } else {
      f(i) = evaluate(X.col(i));
    }
  }
}

template <int Dim>
void PuModel<Dim>::evaluateValidBatch(const Points<Dim>& X, Eigen::VectorXd& f, std::vector<char>& valid) const {
  const Eigen::Index n = X.cols();
  f.resize(n);
  valid.assign(static_cast<std::size_t>(n), 1);
#pragma omp parallel for schedule(dynamic, 256)
  for (Eigen::Index i = 0; i < n; ++i) {
    bool ok = true;
    f(i) = evaluateValid(X.col(i), nullptr, nullptr, &ok);
    valid[static_cast<std::size_t>(i)] = ok ? 1 : 0;
  }
}

template <int Dim>
Box<Dim> PuModel<Dim>::frameBox(const Box<Dim>& box) const {
  if (identityFrame_) return box;
  Box<Dim> yb{Vec<Dim>::Constant(std::numeric_limits<double>::infinity()),
              Vec<Dim>::Constant(-std::numeric_limits<double>::infinity())};
  for (int corner = 0; corner < (1 << Dim); ++corner) {
    Vec<Dim> c;
    for (int k = 0; k < Dim; ++k) c(k) = (corner >> k) & 1 ? box.hi(k) : box.lo(k);
    const Vec<Dim> y = frame_.applyInverse(c);
    yb.lo = yb.lo.cwiseMin(y);
    yb.hi = yb.hi.cwiseMax(y);
  }
  return yb;
}

template <int Dim>
std::unique_ptr<ImplicitField<Dim>> PuModel<Dim>::forGridCells(double cellDiagonal) const {
  if (options_.blend == PuBlend::Hard || !(cellDiagonal > 0)) return nullptr;
  return std::make_unique<PuNearField<Dim>>(*this, cellDiagonal);
}

template <int Dim>
int PuModel<Dim>::nearestSupport(const Vec<Dim>& x, double margin) const {
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  const double m = margin / frame_.q;
  const Box<Dim> query{y - Vec<Dim>::Constant(m), y + Vec<Dim>::Constant(m)};
  int best = -1;
  double bestDistance = std::numeric_limits<double>::infinity();
  forSupportsTouching(query, [&](int i) {
    const double d = leaves_[i].support.distanceTo(y);
    if (d <= m && (d < bestDistance || (d == bestDistance && i < best))) best = i, bestDistance = d;
  });
  return best;
}

template <int Dim>
bool PuModel<Dim>::supportNear(const Box<Dim>& box, double margin) const {
  Box<Dim> yb = frameBox(box);
  yb.lo.array() -= margin / frame_.q;
  yb.hi.array() += margin / frame_.q;
  bool found = false;
  forSupportsTouching(yb, [&](int) { found = true; });
  return found;
}

template <int Dim>
std::vector<std::pair<int, double>> PuModel<Dim>::weights(const Vec<Dim>& x) const {
  std::vector<std::pair<int, double>> out;
  const Vec<Dim> y = identityFrame_ ? x : frame_.applyInverse(x);
  if (options_.blend == PuBlend::Hard) {
    out.emplace_back(tree_.locateLeaf(y), 1.0);
    return out;
  }
  const bool frozen[Dim] = {};
  double S = 0;
  forSupportsAt(y, [&](int i) {
    const double w = bump<Dim>(leaves_[i].support, y, frozen, nullptr, nullptr);
    if (w > 0) {
      out.emplace_back(i, w);
      S += w;
    }
  });
  for (auto& p : out) p.second /= S;
  return out;
}

template <int Dim>
double PuModel<Dim>::lipschitzBound(const Box<Dim>& box) const {
  if (options_.blend == PuBlend::Hard || !(minFactor_ > 1.0)) return std::numeric_limits<double>::infinity();
  const Box<Dim> yb = frameBox(box);
  const Vec<Dim> xc = box.center();
  const double reach = 0.5 * box.extent().norm();
  double sumGF = 0, sumG = 0, fMax = 0, lMax = 0, sMin = 0, factorMin = std::numeric_limits<double>::infinity();
  int touching = 0;
  forSupportsTouching(yb, [&](int i) {
    ++touching;
    const Leaf& leaf = leaves_[i];
    factorMin = std::min(factorMin, leaf.factor);
    double inv2 = 0, wMin = 1;
    for (int k = 0; k < Dim; ++k) {
      const double c = 0.5 * (leaf.support.lo(k) + leaf.support.hi(k));
      const double h = 0.5 * (leaf.support.hi(k) - leaf.support.lo(k));
      inv2 += 1.0 / (h * h);
      const double t = std::max(std::abs(yb.lo(k) - c), std::abs(yb.hi(k) - c)) / h;
      const double u = 1.0 - t * t;
      wMin *= u > 0 ? u * u * u : 0.0;
    }
    const double G = kMaxBumpSlope * std::sqrt(inv2) / frame_.q;  // ≥ ‖∇ₓwᵢ‖
    const double L = leaf.model.lipschitzBound(box);
    const double F = std::abs(leaf.model.value(xc)) + L * reach;  // ≥ |fᵢ| on the box
    sumGF += G * F;
    sumG += G;
    fMax = std::max(fMax, F);
    lMax = std::max(lMax, L);
    sMin += wMin;
  });
  if (touching == 0) return 0.0;  // no data reaches the box: f is the constant noDataValue()
  // Every point of a blended leaf box lies in its support, σ ≥ factorMin times larger (the leaf's
  // support touches yb): there |tₖ| ≤ 1/σ on every axis, so S ≥ (1 − 1/factorMin²)^(3·Dim) where
  // such boxes cover yb. The smallest factor of the supports here, not of the whole model: one
  // capped support elsewhere must not loosen every bound.
  if (factorMin > 1.0 && coveredByData(yb)) sMin = std::max(sMin, std::pow(1.0 - 1.0 / (factorMin * factorMin), 3 * Dim));
  // Where S has no positive lower bound f may jump to noDataValue(): no finite bound.
  if (!(sMin > 0)) return std::numeric_limits<double>::infinity();
  // Rounding of the sums: a relative 1e-12 margin.
  return (1.0 + 1e-12) * ((sumGF + fMax * sumG) / sMin + lMax);
}

namespace {

// The tree's options of a PU fit (pu_tree.h).
PuTreeOptions treeOptionsOf(const PuOptions& options, const SupportLimits& limits) {
  PuTreeOptions tree;
  tree.maxPointsPerBox = options.maxPointsPerBox;
  tree.boxSize = options.boxSize;
  tree.maxSupportSamples = limits.max;
  tree.overlap = options.overlap;
  tree.splitEmpty = options.blend == PuBlend::Hard;
  tree.cancel = options.local.cancel;
  return tree;
}

}  // namespace

template <int Dim>
PuModel<Dim> fitPu(const HermiteSamples<Dim>& samples, const PuOptions& options, PuReport* report,
                   const Similarity<Dim>& frame) {
  const auto t0 = std::chrono::steady_clock::now();
  if (samples.size() < 1) throw InputError("partition: no samples");
  if (!(options.overlap >= 1)) throw InputError("partition: overlap must be >= 1");
  if (!(options.growth > 1)) throw InputError("partition: growth must be > 1");
  if (!(options.vertexReach > 0) || !std::isfinite(options.vertexReach))
    throw InputError("partition: the zero-set reach must be a finite number > 0");
  const int n = samples.size();
  const bool identity = isIdentity(frame);
  Points<Dim> Y;
  if (!identity) {
    Y.resize(Dim, n);
    for (int i = 0; i < n; ++i) Y.col(i) = frame.applyInverse(samples.points.col(i));
  }
  const Points<Dim>& frameY = identity ? samples.points : Y;
  const SupportLimits limits = supportLimits<Dim>(options);
  PuTree<Dim> tree(frameY, treeOptionsOf(options, limits));
  PuDataReach<Dim> dataReach;
  std::vector<char> blended = blendedLeaves<Dim>(tree, options.blend, options.overlap);
  HrbfOptions local = options.local;
  local.kernel.radius *= frame.q;
  const LeafFitter<Dim> sizer(samples, tree, options, local, limits, blended, nullptr);  // supports only
  splitCrowdedBlended<Dim>(tree, blended, options, sizer, limits);
  if (options.blend == PuBlend::Smooth) {
    // Normals in frame coordinates: y = R⁻¹(x − t)/q turns directions by R⁻¹ = Rᵀ.
    Points<Dim> frameN;
    if (!identity) frameN = frame.R.transpose() * samples.normals;
    dataReach = PuDataReach<Dim>(tree, frameY, options.dataReach, identity ? &samples.normals : &frameN,
                                 options.edgeShift, options.local.cancel);
    refineCover<Dim>(tree, dataReach, blended, options.local.cancel);
  }
  throwIfCancelled(options.local.cancel);
  const double treeMs = msSince(t0);
  const auto leafCount = static_cast<std::size_t>(tree.leafCount());
  std::vector<typename PuModel<Dim>::Leaf> leaves(leafCount);
  std::vector<FitReport> reports(leafCount);
  blendReachCover<Dim>(tree, dataReach, blended);
  throwIfCancelled(options.local.cancel);
  for (std::size_t i = 0; i < leafCount; ++i) leaves[i].blended = blended[i] != 0;
  checkLocalFitMemory<Dim>(n, limits, local);
  const PuDataReach<Dim>* reach = dataReach.empty() ? nullptr : &dataReach;
  fitLeaves<Dim>(LeafFitter<Dim>(samples, tree, options, local, limits, blended, reach), leaves, reports);
  if (report) {
    *report = summariseFits<Dim>(tree, leaves, reports, options, local);
    report->treeMs = treeMs;
    report->fitMs = msSince(t0);
  }
  // Freed on both threads: one local report per box, each with a solver name on the heap.
  const int boxes = static_cast<int>(reports.size());
#pragma omp parallel for schedule(static)
  for (int i = 0; i < boxes; ++i) reports[static_cast<std::size_t>(i)] = FitReport{};
  return PuModel<Dim>(std::move(tree), std::move(leaves), options, frame, std::move(dataReach));
}

template <int Dim>
PuModel<Dim> transformPu(const PuModel<Dim>& model, const Similarity<Dim>& T) {
  std::vector<typename PuModel<Dim>::Leaf> leaves = model.leaves();
  const int count = static_cast<int>(leaves.size());
#pragma omp parallel for schedule(dynamic, 64)
  for (int i = 0; i < count; ++i)
    if (leaves[i].blended) leaves[i].model = transformModel<Dim>(leaves[i].model, T);
  return PuModel<Dim>(model.tree(), std::move(leaves), model.options(), composeSimilarity<Dim>(T, model.frame()),
                      model.dataReach());
}

template class PuModel<2>;
template class PuModel<3>;
template PuModel<2> fitPu<2>(const HermiteSamples<2>&, const PuOptions&, PuReport*, const Similarity<2>&);
template PuModel<3> fitPu<3>(const HermiteSamples<3>&, const PuOptions&, PuReport*, const Similarity<3>&);
template PuModel<2> transformPu<2>(const PuModel<2>&, const Similarity<2>&);
template PuModel<3> transformPu<3>(const PuModel<3>&, const Similarity<3>&);
template Similarity<2> composeSimilarity<2>(const Similarity<2>&, const Similarity<2>&);
template Similarity<3> composeSimilarity<3>(const Similarity<3>&, const Similarity<3>&);

}  // namespace hermite
