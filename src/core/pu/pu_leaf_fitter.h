#pragma once
// The local fit of each box of a partition of unity (pu_fit.cpp): its support's samples (the
// overlap, grown to the fewest a fit takes or shrunk to the most), the fit, and the refit across
// an edge (docs/maths.md, Partition of unity). Internal to the PU fit.

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/pu/pu_bump.h"
#include "core/pu/pu_local_fit.h"
#include "core/pu/pu_model.h"

namespace hermite::detail {

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
      dist[j] = scaledDistance<Dim>(Y.col(scratch.pos[j]), c, invH);
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

}  // namespace hermite::detail
