#include "core/points/normal_estimation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <queue>
#include <string>
#include <vector>

#include <Eigen/Eigenvalues>
#include <nanoflann.hpp>

#include "core/base/errors.h"

namespace hermite {

namespace {

// nanoflann's dataset interface over a Dim × N column matrix.
template <int Dim>
struct CloudAdaptor {
  const Points<Dim>& P;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(P.cols()); }
  double kdtree_get_pt(std::size_t i, std::size_t k) const { return P(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)); }
  template <class B>
  bool kdtree_get_bbox(B&) const { return false; }
};

template <int Dim>
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CloudAdaptor<Dim>>,
                                                   CloudAdaptor<Dim>, Dim, std::uint32_t>;

// The symmetric k-nearest-neighbour graph: `nbr` holds each point's k nearest (itself included,
// row-major N × k), `reverse` the points that list it.
struct NeighbourGraph {
  int k = 0;
  std::vector<std::uint32_t> nbr;
  std::vector<std::vector<std::uint32_t>> reverse;
  const std::uint32_t* of(int i) const { return nbr.data() + static_cast<std::size_t>(i) * k; }
};

template <int Dim>
NeighbourGraph neighbourGraph(const Points<Dim>& points, int k) {
  const int n = static_cast<int>(points.cols());
  NeighbourGraph g;
  g.k = k;
  g.nbr.resize(static_cast<std::size_t>(n) * k);
  CloudAdaptor<Dim> cloud{points};
  KdTree<Dim> tree(Dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
#pragma omp parallel
  {
    std::vector<double> d2(static_cast<std::size_t>(k));
#pragma omp for schedule(dynamic, 1024)
    for (int i = 0; i < n; ++i) {
      std::uint32_t* idx = g.nbr.data() + static_cast<std::size_t>(i) * k;
      const Vec<Dim> p = points.col(i);
      const std::size_t found = tree.knnSearch(p.data(), static_cast<std::size_t>(k), idx, d2.data());
      for (std::size_t j = found; j < static_cast<std::size_t>(k); ++j) idx[j] = static_cast<std::uint32_t>(i);
    }
  }
  g.reverse.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) {
      const std::uint32_t o = g.of(i)[j];
      if (static_cast<int>(o) != i) g.reverse[o].push_back(static_cast<std::uint32_t>(i));
    }
  return g;
}

// The smallest-eigenvalue eigenvector of a covariance, unit (UnitX when it is not finite).
template <int Dim>
Vec<Dim> smallestEigenvector(const Mat<Dim>& C) {
  Eigen::SelfAdjointEigenSolver<Mat<Dim>> eig(C);
  Vec<Dim> nrm = eig.eigenvectors().col(0);  // smallest eigenvalue first
  if (!(nrm.norm() > 0) || !nrm.allFinite()) nrm = Vec<Dim>::UnitX();
  return nrm.normalized();
}

// The unit eigenvector of the smallest eigenvalue of the covariance of the points `idx`.
template <int Dim>
Vec<Dim> pcaNormal(const Points<Dim>& points, const std::uint32_t* idx, int count) {
  Vec<Dim> mean = Vec<Dim>::Zero();
  for (int j = 0; j < count; ++j) mean += points.col(idx[j]);
  mean /= count;
  Mat<Dim> C = Mat<Dim>::Zero();
  for (int j = 0; j < count; ++j) {
    const Vec<Dim> d = points.col(idx[j]) - mean;
    C += d * d.transpose();
  }
  return smallestEigenvector<Dim>(C);
}

// The sheet band of each point: sheetBand × the distance to its k-th nearest neighbour (the
// neighbourhood radius). Neighbours farther than that from a point's tangent plane lie on
// another sheet (or across a crease); see sheetNormal and edgeRule.
template <int Dim>
std::vector<double> sheetBands(const Points<Dim>& points, const NeighbourGraph& g, double sheetBand) {
  const int n = static_cast<int>(points.cols());
  std::vector<double> band(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    double radius = 0;
    for (int j = 0; j < g.k; ++j) radius = std::max(radius, (points.col(g.of(i)[j]) - points.col(i)).norm());
    band[i] = sheetBand * radius;
  }
  return band;
}

// The normal of the hyperplane through Dim points `q` (columns), or zero when they span none.
template <int Dim>
Vec<Dim> spanNormal(const Mat<Dim>& q) {
  if constexpr (Dim == 2) {
    const Vec<2> a = q.col(1) - q.col(0);
    return Vec<2>(-a.y(), a.x());
  } else {
    return (q.col(1) - q.col(0)).cross(q.col(2) - q.col(0));
  }
}

// A local model of the k neighbourhood of pᵢ (offsets h = n·(pⱼ − pᵢ)): the sheet through pᵢ,
// and, when `twoSheets`, a parallel sheet at offset `second`.
template <int Dim>
struct SheetModel {
  Vec<Dim> normal = Vec<Dim>::UnitX();
  double second = 0;
  bool twoSheets = false;
  double score = std::numeric_limits<double>::infinity();
};

// The best one-sheet and two-sheet models of a neighbourhood (Q: Dim × k, the neighbours minus
// pᵢ) over the candidate normals of the hyperplanes through Dim of its points (sheetNormal).
template <int Dim>
std::pair<SheetModel<Dim>, SheetModel<Dim>> fitSheets(const Eigen::Matrix<double, Dim, Eigen::Dynamic>& Q, double band) {
  const int k = static_cast<int>(Q.cols());
  const double band2 = band * band;
  SheetModel<Dim> one, two;
  auto consider = [&](Vec<Dim> nrm) {
    const double len = nrm.norm();
    if (!(len > 1e-12 * band2)) return;
    nrm /= len;
    // One sheet through pᵢ; the second at the mean offset of the outliers on the side with more.
    double s1 = 0, up = 0, down = 0;
    int nUp = 0, nDown = 0;
    for (int j = 0; j < k; ++j) {
      const double h = nrm.dot(Q.col(j));
      s1 += std::min(band2, h * h);
      if (h > band) up += h, ++nUp;
      if (h < -band) down += h, ++nDown;
    }
    if (s1 < one.score) one = {nrm, 0, false, s1};
    if (std::max(nUp, nDown) < 2) return;
    const double c = nUp >= nDown ? up / nUp : down / nDown;
    double s2 = 0;
    for (int j = 0; j < k; ++j) {
      const double h = nrm.dot(Q.col(j));
      s2 += std::min(band2, std::min(h * h, (h - c) * (h - c)));
    }
    if (s2 < two.score) two = {nrm, c, true, s2};
  };
  Mat<Dim> q;
  if constexpr (Dim == 2) {
    for (int a = 0; a < k; ++a)
      for (int b = a + 1; b < k; ++b) {
        q << Q.col(a), Q.col(b);
        consider(spanNormal<Dim>(q));
      }
  } else {
    for (int a = 0; a < k; ++a)
      for (int b = a + 1; b < k; ++b)
        for (int c = b + 1; c < k; ++c) {
          q << Q.col(a), Q.col(b), Q.col(c);
          consider(spanNormal<Dim>(q));
        }
  }
  return {one, two};
}

// The normal of model m refitted to its inliers (|h| ≤ band on pᵢ's sheet, |h − c| ≤ band on the
// second), each sheet about its own mean; `second` receives c times it. `fallback` when fewer
// than Dim + 1 fit.
template <int Dim>
Vec<Dim> refitSheets(const Eigen::Matrix<double, Dim, Eigen::Dynamic>& Q, const SheetModel<Dim>& m, double band,
                     const Vec<Dim>& fallback, Vec<Dim>& second) {
  Vec<Dim> sum[2] = {Vec<Dim>::Zero(), Vec<Dim>::Zero()};
  Mat<Dim> outer = Mat<Dim>::Zero();
  int count[2] = {0, 0};
  for (Eigen::Index j = 0; j < Q.cols(); ++j) {
    const double h = m.normal.dot(Q.col(j));
    const int sheet = std::abs(h) <= band ? 0 : m.twoSheets && std::abs(h - m.second) <= band ? 1 : -1;
    if (sheet < 0) continue;
    sum[sheet] += Q.col(j);
    outer += Q.col(j) * Q.col(j).transpose();
    ++count[sheet];
  }
  if (count[0] + count[1] < Dim + 1) return fallback;
  Mat<Dim> C = outer;
  for (int sh = 0; sh < 2; ++sh)
    if (count[sh] > 0) C -= sum[sh] * sum[sh].transpose() / count[sh];
  const Vec<Dim> nrm = smallestEigenvector<Dim>(C);
  if (m.twoSheets && count[1] > 0) second = nrm * nrm.dot(sum[1] / count[1]);
  return nrm;
}

// Point i's normal, robust to a second sheet among its neighbours (docs/maths.md): every
// hyperplane through Dim of the k neighbourhood points (pᵢ included; 120 for k = 10 in 3D) gives
// a candidate normal n, scored by its truncated squared residual Σ min(r², band²) over the k
// (MSAC: inliers count by how well they fit, every outlier costs band²), once as one sheet
// through pᵢ (r = h = n·(pⱼ − pᵢ)) and once as two parallel sheets, through pᵢ and at the mean
// offset c of the neighbours beyond the band on the side holding more of them (at least 2),
// r = min(|h|, |h − c|). A candidate spanned by the other sheet's points gives the second model
// its exact normal even when pᵢ's own sheet holds only 3 of the k. Two sheets are taken when
// they fit at least two neighbours' worth (2·band²) better than the best single sheet: on one
// sheet, flat or mildly curved, every neighbour already fits within the band and they cannot.
// The normal is the smallest eigenvector of the inliers' covariance, each sheet about its own
// mean (parallel sheets share their normal, so all inliers estimate it); `second` receives the
// second sheet's offset times that normal (zero for one sheet). Plain PCA over all k when fewer
// than Dim + 1 fit, and at once (no search) when PCA's hyperplane fits all k as one sheet (below).
template <int Dim>
Vec<Dim> sheetNormal(const Points<Dim>& points, const NeighbourGraph& g, int i, double band, Vec<Dim>& second) {
  const std::uint32_t* idx = g.of(i);
  Eigen::Matrix<double, Dim, Eigen::Dynamic> Q(Dim, g.k);
  for (int j = 0; j < g.k; ++j) Q.col(j) = points.col(idx[j]) - points.col(i);
  second = Vec<Dim>::Zero();
  // One sheet (most points): PCA's hyperplane through pᵢ holds all k within band / 2. In 2D also
  // when the line through their mean holds them within 0.75·band: the k samples of a curve span
  // k spacings of arc (a 3D neighbourhood is a disc ~1.8 spacings across), so curvature, not a
  // second sheet, moves its ends off the tangent (10 of 40 samples on a circle: ±0.15·r).
  const Vec<Dim> pca = pcaNormal<Dim>(points, idx, g.k);
  const Eigen::Matrix<double, 1, Eigen::Dynamic> off = pca.transpose() * Q;
  if (off.cwiseAbs().maxCoeff() <= 0.5 * band) return pca;
  if (Dim == 2 && (off.array() - off.mean()).abs().maxCoeff() <= 0.75 * band) return pca;
  const auto [one, two] = fitSheets<Dim>(Q, band);
  return refitSheets<Dim>(Q, two.score <= one.score - 2 * band * band ? two : one, band, pca, second);
}

// How an orientation crosses the edge i → j, and at what cost (see the header). `flip` says
// whether nⱼ as it stands must change sign to follow nᵢ as it stands (i is the oriented end).
// With d = pⱼ − pᵢ, the offsets oᵢ = |d·n̂ᵢ|, oⱼ = |d·n̂ⱼ| against the sheet bands bᵢ, bⱼ say whether
// each end sees the other on its own sheet (o ≤ b) or off it:
//   along a sheet   both on one sheet, d in both tangent planes (within asin gapSine), normals
//                   agree: copy (flip when nᵢ·nⱼ < 0), cost 1 − |nᵢ·nⱼ| < 1;
//   across a gap    both off one another's sheet (or d along both normals, the old test kept for
//                   infinite bands), normals parallel, and the two sign rules below agree: the
//                   sheets of a closed surface face each other there, so nⱼ takes the opposite
//                   orientation, cost 2 + (1 − |nᵢ·nⱼ|) + (1 − the smaller |d̂·n|);
//   any other edge  (a crease, a fold, noise), the last resort at cost 4 + (1 − its margin):
//                   where d leaves both tangent planes more steeply than the normals agree
//                   (min |d̂·n| > |nᵢ·nⱼ|, a sharp crease) by the crease rule — across a crease
//                   of a consistently oriented surface, convex or concave, d·nᵢ and d·nⱼ have
//                   opposite signs — with margin min |d̂·n|; else copy, margin |nᵢ·nⱼ|.
// A neighbour on the other sheet a lateral distance away from pᵢ makes a shallow d (within 30° of
// both planes once the gap is under ~1.7 times that distance), which the angles alone took for
// an edge along a sheet, copying the orientation across the gap at cost < 1; the bands reject it.
// Along a sheet and across a gap need both ends `trusted` (agreesWithNeighbours); an edge to an
// outlier line is always the last resort. Infinite bands and zero second sheets give the
// angle-only rules (orientationDisagreement, which has no sheet models).
enum class EdgeKind { Along, Across, Crease, Other };

struct EdgeRule {
  double cost = 0;
  bool flip = false;
  EdgeKind kind = EdgeKind::Other;
};

template <int Dim>
EdgeRule edgeRule(const Points<Dim>& P, const Points<Dim>& N, int i, int j, const NormalEstimationOptions& o,
                  double bandI, double bandJ, const Vec<Dim>& secondI, const Vec<Dim>& secondJ,
                  bool trusted = true) {
  const Vec<Dim> ni = N.col(i).normalized(), nj = N.col(j).normalized();
  const double dot = ni.dot(nj), agree = std::abs(dot);
  const Vec<Dim> d = P.col(j) - P.col(i);
  const double len = d.norm();
  if (!(len > 0)) return {1.0 - agree, dot < 0, EdgeKind::Along};  // a duplicate point: the same sheet
  const double oi = d.dot(ni), oj = d.dot(nj);
  const double li = std::abs(oi) / len, lj = std::abs(oj) / len;
  // Each end sees the other off its sheet when beyond its band or nearer its second sheet (the
  // offset of the second sheet is secondI·n̂ᵢ from pᵢ; zero when pᵢ saw none).
  const double ci = secondI.dot(ni), cj = secondJ.dot(nj);
  const bool offI = std::abs(oi) > bandI || (ci != 0 && std::abs(oi - ci) < std::abs(oi));
  const bool offJ = std::abs(oj) > bandJ || (cj != 0 && std::abs(oj + cj) < std::abs(oj));
  const bool oneSheet = !offI && !offJ;
  const bool offSheets = offI && offJ;
  if (trusted && oneSheet && agree >= o.agreeCosine && std::max(li, lj) <= o.gapSine)
    return {1.0 - agree, dot < 0, EdgeKind::Along};
  const bool creaseFlip = oi * oj > 0;
  const bool steep = std::min(li, lj) >= o.acrossCosine;
  if (trusted && agree >= o.acrossCosine && (offSheets || steep) && creaseFlip == (dot > 0))
    return {2.0 + (1.0 - agree) + (1.0 - std::min(li, lj)), dot > 0, EdgeKind::Across};
  if (std::min(li, lj) > agree) return {4.0 + (1.0 - std::min(li, lj)), creaseFlip, EdgeKind::Crease};
  return {4.0 + (1.0 - agree), dot < 0, EdgeKind::Other};
}

// Whether each normal line agrees (within 30°) with at least a third of its k − 1 neighbours'
// lines. A line that does not is an outlier (a neighbourhood that no sheet model fits: a thin
// rim, a clump of samples), and an edge to it is no evidence for the orientation: edgeRule
// then takes it only as a last resort. Two bad lines side by side can otherwise pass as an edge
// along a sheet between the two sheets of a thin part and copy an orientation across the gap.
template <int Dim>
std::vector<char> agreesWithNeighbours(const Points<Dim>& N, const NeighbourGraph& g) {
  const int n = static_cast<int>(N.cols());
  std::vector<char> ok(static_cast<std::size_t>(n));
  const double cos30 = std::sqrt(3.0) / 2;
#pragma omp parallel for schedule(static)
  for (int i = 0; i < n; ++i) {
    const Vec<Dim> ni = N.col(i).normalized();
    int agree = 0;
    for (int j = 0; j < g.k; ++j)
      if (static_cast<int>(g.of(i)[j]) != i) agree += std::abs(ni.dot(N.col(g.of(i)[j]).normalized())) >= cos30;
    ok[i] = 3 * agree >= g.k - 1;
  }
  return ok;
}

// The next seed among the points not yet oriented: per axis the one with the largest coordinate
// (`order` holds each axis's indices by decreasing coordinate, `cursor` skips oriented ones),
// over the axes the one whose normal is most aligned with its axis. Returns −1 when all are done.
template <int Dim>
int nextSeed(const Points<Dim>& N, const std::vector<char>& done, const std::vector<std::vector<int>>& order,
             std::vector<std::size_t>& cursor, int& axis) {
  int best = -1;
  double bestAlign = -1;
  for (int a = 0; a < Dim; ++a) {
    while (cursor[a] < order[a].size() && done[order[a][cursor[a]]]) ++cursor[a];
    if (cursor[a] == order[a].size()) return -1;
    const int i = order[a][cursor[a]];
    const double align = std::abs(N(a, i)) / N.col(i).norm();
    if (align > bestAlign) bestAlign = align, best = i, axis = a;
  }
  return best;
}

// Patches: small pieces of one sheet, each grown by Prim's tree from an unassigned point over the
// cheapest trusted edges along a sheet (EdgeRule), at most `maxPatch` points, its normals
// oriented along the tree. Points with `fixed` set are patches of their own. Returns each
// point's patch; `patches` receives their count.
template <int Dim>
std::vector<int> growPatches(const Points<Dim>& P, Points<Dim>& N, const std::vector<char>& fixed, const NeighbourGraph& g,
                             const std::vector<double>& band, const Points<Dim>& second,
                             const std::vector<char>& trusted, const NormalEstimationOptions& o, int maxPatch,
                             int& patches) {
  const int n = static_cast<int>(P.cols());
  struct Item {
    double cost;
    std::uint32_t child;
    bool flip;
    bool operator>(const Item& x) const { return cost > x.cost; }
  };
  std::vector<int> patch(static_cast<std::size_t>(n), -1);
  patches = 0;
  for (int s = 0; s < n; ++s) {
    if (patch[s] >= 0) continue;
    const int id = patches++;
    patch[s] = id;
    if (fixed[s]) continue;
    std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
    auto push = [&](std::uint32_t from) {
      auto edge = [&](std::uint32_t to) {
        if (patch[to] >= 0 || fixed[to]) return;
        const EdgeRule r = edgeRule<Dim>(P, N, int(from), int(to), o, band[from], band[to], second.col(from),
                                         second.col(to), trusted[from] && trusted[to]);
        if (r.kind == EdgeKind::Along) heap.push({r.cost, to, r.flip});
      };
      for (int j = 0; j < g.k; ++j) edge(g.of(int(from))[j]);
      for (std::uint32_t to : g.reverse[from]) edge(to);
    };
    push(static_cast<std::uint32_t>(s));
    for (int size = 1; size < maxPatch && !heap.empty();) {
      const Item e = heap.top();
      heap.pop();
      if (patch[e.child] >= 0) continue;
      patch[e.child] = id;
      if (e.flip) N.col(e.child) = -N.col(e.child);
      ++size;
      push(e.child);
    }
  }
  return patch;
}

// The evidence between patches: for each k-nearest-neighbour edge whose ends lie in different
// patches, +w when its EdgeRule keeps the two normals as they stand, −w when it flips one;
// w = 1 for edges along a sheet and across a gap, 0.1 for the rest (creases, folds, noise).
// Returns, per patch, its neighbouring patches with the summed evidence.
template <int Dim>
std::vector<std::vector<std::pair<int, double>>> patchVotes(const Points<Dim>& P, const Points<Dim>& N,
                                                            const std::vector<int>& patch, int patches,
                                                            const NeighbourGraph& g, const std::vector<double>& band,
                                                            const Points<Dim>& second, const std::vector<char>& trusted,
                                                            const NormalEstimationOptions& o) {
  const int n = static_cast<int>(P.cols());
  std::vector<std::pair<std::uint64_t, double>> votes;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < g.k; ++k) {
      const int j = static_cast<int>(g.of(i)[k]);
      if (patch[i] == patch[j]) continue;
      const EdgeRule r = edgeRule<Dim>(P, N, i, j, o, band[i], band[j], second.col(i), second.col(j),
                                       trusted[i] && trusted[j]);
      const double w = r.kind == EdgeKind::Along || r.kind == EdgeKind::Across ? 1.0 : 0.1;
      const std::uint64_t a = static_cast<std::uint64_t>(std::min(patch[i], patch[j]));
      const std::uint64_t b = static_cast<std::uint64_t>(std::max(patch[i], patch[j]));
      votes.push_back({a << 32 | b, r.flip ? -w : w});
    }
  std::sort(votes.begin(), votes.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<std::vector<std::pair<int, double>>> adj(static_cast<std::size_t>(patches));
  for (std::size_t v = 0; v < votes.size();) {
    double sum = 0;
    std::size_t e = v;
    for (; e < votes.size() && votes[e].first == votes[v].first; ++e) sum += votes[e].second;
    const int a = static_cast<int>(votes[v].first >> 32), b = static_cast<int>(votes[v].first & 0xffffffffu);
    adj[a].push_back({b, sum});
    adj[b].push_back({a, sum});
    v = e;
  }
  return adj;
}

// Orients the normals of the points with `done[i]` == 0 (docs/maths.md): patches first
// (growPatches), then a maximum spanning tree of the patch graph by the size of the summed
// evidence between patches (patchVotes), from the patches of the points already done, then from
// seeds; each tree edge turns the child patch over when its evidence says so. One wrong edge (a
// bad normal, a rim a spacing wide between two sheets) no longer decides a whole sheet: two
// sheets of a thin part are tied by dozens of edges across the gap. Fragments (patches of fewer
// than maxPatch / 2 points: rims, creases, clumps of outlier lines, whose normals are least
// sure) pass their orientation on only when no whole patch or given normal reaches further.
// `part` (when given, N entries) receives each point's tree: −1 for the trees grown from the
// points already done, else the index of its seed in seeding order.
template <int Dim>
void orientNormals(const Points<Dim>& P, Points<Dim>& N, std::vector<char> done, const NeighbourGraph& g,
                   const std::vector<double>& band, const Points<Dim>& second, const NormalEstimationOptions& o,
                   std::vector<int>* part = nullptr) {
  const int n = static_cast<int>(P.cols());
  const std::vector<char> trusted = agreesWithNeighbours<Dim>(N, g);
  int patches = 0;
  const int maxPatch = 16;  // points per patch: a neighbourhood or two across (see growPatches)
  const std::vector<int> patch = growPatches<Dim>(P, N, done, g, band, second, trusted, o, maxPatch, patches);
  const auto adj = patchVotes<Dim>(P, N, patch, patches, g, band, second, trusted, o);
  std::vector<std::vector<int>> members(static_cast<std::size_t>(patches));
  for (int i = 0; i < n; ++i) members[patch[i]].push_back(i);
  std::vector<char> patchDone(static_cast<std::size_t>(patches), 0);
  std::vector<int> patchTree(static_cast<std::size_t>(patches), -1);
  struct Item {
    bool relay;  // the parent is a given normal or a whole patch (maxPatch / 2 points or more)
    double strength;
    int child, parent;
    bool flip;
    bool operator<(const Item& x) const { return relay != x.relay ? !relay : strength < x.strength; }
  };
  std::priority_queue<Item> heap;  // strongest evidence first
  // The evidence compares the patches as grown; a child turns over when its parent did, or when the
  // evidence is negative, not both.
  auto finish = [&](int a, bool flip, bool given) {
    patchDone[a] = 1;
    const bool relays = given || 2 * static_cast<int>(members[a].size()) >= maxPatch;
    for (int i : members[a]) {
      done[i] = 1;
      if (flip) N.col(i) = -N.col(i);
    }
    for (const auto& [b, sum] : adj[a])
      if (!patchDone[b]) heap.push({relays, std::abs(sum), b, a, (sum < 0) != (flip != 0)});
  };
  for (int a = 0; a < patches; ++a)
    if (done[members[a].front()]) finish(a, false, true);
  std::vector<std::vector<int>> order(Dim, std::vector<int>(static_cast<std::size_t>(n)));
  for (int a = 0; a < Dim; ++a) {
    std::iota(order[a].begin(), order[a].end(), 0);
    std::sort(order[a].begin(), order[a].end(), [&](int x, int y) { return P(a, x) > P(a, y); });
  }
  std::vector<std::size_t> cursor(Dim, 0);
  for (int tree = 0;; ++tree) {
    while (!heap.empty()) {
      const Item e = heap.top();
      heap.pop();
      if (patchDone[e.child]) continue;
      patchTree[e.child] = patchTree[e.parent];
      finish(e.child, e.flip, false);
    }
    int axis = 0;
    const int seed = nextSeed<Dim>(N, done, order, cursor, axis);
    if (seed < 0) break;
    patchTree[patch[seed]] = tree;
    finish(patch[seed], N(axis, seed) < 0, false);
  }
  if (part)
    for (int i = 0; i < n; ++i) (*part)[i] = patchTree[patch[i]];
}

// Per tree (`part`, from orientNormals), the sign that makes the oriented normals agree with
// the most given ones (`given`, same shape): turns the tree over when at most a third of its
// given signs agree with the propagation. Between a third and two thirds the given signs say
// nothing (unoriented data) and the seed's outward rule stands.
template <int Dim>
void followGivenMajority(Points<Dim>& N, const Points<Dim>& given, const std::vector<int>& part) {
  const int trees = part.empty() ? 0 : *std::max_element(part.begin(), part.end()) + 1;
  std::vector<long> agree(static_cast<std::size_t>(trees), 0), total(static_cast<std::size_t>(trees), 0);
  for (std::size_t i = 0; i < part.size(); ++i) {
    if (part[i] < 0) continue;
    const Eigen::Index c = static_cast<Eigen::Index>(i);
    agree[part[i]] += N.col(c).dot(given.col(c)) > 0;
    ++total[part[i]];
  }
  for (std::size_t i = 0; i < part.size(); ++i)
    if (part[i] >= 0 && 3 * agree[part[i]] <= total[part[i]]) N.col(static_cast<Eigen::Index>(i)) *= -1;
}

}  // namespace

template <int Dim>
int completeNormals(const Points<Dim>& points, Points<Dim>& normals, const NormalEstimationOptions& options) {
  const int n = static_cast<int>(points.cols());
  std::vector<char> known(static_cast<std::size_t>(n));
  int missing = 0;
  for (int i = 0; i < n; ++i) {
    known[i] = normals.col(i).isZero(0) ? 0 : 1;
    missing += 1 - known[i];
  }
  if (missing == 0) return 0;
  if (n < 2)
    throw InputError("normal estimation: needs at least 2 points (got " + std::to_string(n) + ")");
  const int k = std::min(std::max(options.neighbours, Dim), n);
  const NeighbourGraph g = neighbourGraph<Dim>(points, k);
  const std::vector<double> band = sheetBands<Dim>(points, g, options.sheetBand);
  Points<Dim> second = Points<Dim>::Zero(Dim, n);  // per point: its second sheet's offset × normal
#pragma omp parallel for schedule(dynamic, 1024)
  for (int i = 0; i < n; ++i)
    if (!known[i]) {
      Vec<Dim> c;
      normals.col(i) = sheetNormal<Dim>(points, g, i, band[i], c);
      second.col(i) = c;
    }
  orientNormals<Dim>(points, normals, std::move(known), g, band, second, options);
  return missing;
}

template <int Dim>
double orientationDisagreement(const Points<Dim>& points, const Points<Dim>& normals,
                               const NormalEstimationOptions& options) {
  const int n = static_cast<int>(points.cols());
  if (n < 2) return 0;
  const int k = std::min(std::max(options.neighbours, Dim), n);
  // At most 50 000 evenly strided points query their neighbours (the tree holds all): a loader
  // runs this on every file with normals, and the fraction needs no more.
  const int stride = std::max(1, n / 50000);
  CloudAdaptor<Dim> cloud{points};
  KdTree<Dim> tree(Dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  const double inf = std::numeric_limits<double>::infinity();
  long edges = 0, flips = 0;  // edges along a sheet, and those whose normals point opposite ways
#pragma omp parallel reduction(+ : edges, flips)
  {
    std::vector<std::uint32_t> idx(static_cast<std::size_t>(k));
    std::vector<double> d2(static_cast<std::size_t>(k));
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < n; i += stride) {
      if (normals.col(i).isZero(0)) continue;
      const Vec<Dim> p = points.col(i);
      const std::size_t found = tree.knnSearch(p.data(), static_cast<std::size_t>(k), idx.data(), d2.data());
      for (std::size_t j = 0; j < found; ++j) {
        const int o = static_cast<int>(idx[j]);
        if (o == i || normals.col(o).isZero(0)) continue;
        const EdgeRule r = edgeRule<Dim>(points, normals, i, o, options, inf, inf, Vec<Dim>::Zero(), Vec<Dim>::Zero());  // angles only
        if (r.kind != EdgeKind::Along) continue;  // creases and gaps: noise makes their rules unsure
        ++edges;
        flips += r.flip;
      }
    }
  }
  return edges == 0 ? 0.0 : double(flips) / double(edges);
}

template <int Dim>
int orientNormalLines(const Points<Dim>& points, Points<Dim>& normals, const NormalEstimationOptions& options) {
  const int n = static_cast<int>(points.cols());
  for (int i = 0; i < n; ++i)
    if (normals.col(i).isZero(0))
      throw InputError("normal orientation: normal " + std::to_string(i) + " is zero (estimate it first)");
  if (n < 2) return 0;
  const NeighbourGraph g = neighbourGraph<Dim>(points, std::min(std::max(options.neighbours, Dim), n));
  const Points<Dim> given = normals;
  std::vector<int> part(static_cast<std::size_t>(n), -1);
  orientNormals<Dim>(points, normals, std::vector<char>(static_cast<std::size_t>(n), 0), g,
                     sheetBands<Dim>(points, g, options.sheetBand), Points<Dim>::Zero(Dim, n), options, &part);
  followGivenMajority<Dim>(normals, given, part);
  int flipped = 0;
  for (int i = 0; i < n; ++i) flipped += normals.col(i).dot(given.col(i)) < 0;
  return flipped;
}

template <int Dim>
Points<Dim> estimateNormals(const Points<Dim>& points, const NormalEstimationOptions& options) {
  const int n = static_cast<int>(points.cols());
  if (n < 2) throw InputError("normal estimation: needs at least 2 points (got " + std::to_string(n) + ")");
  Points<Dim> normals = Points<Dim>::Zero(Dim, n);
  completeNormals<Dim>(points, normals, options);
  return normals;
}

template Points<2> estimateNormals<2>(const Points<2>&, const NormalEstimationOptions&);
template Points<3> estimateNormals<3>(const Points<3>&, const NormalEstimationOptions&);
template int completeNormals<2>(const Points<2>&, Points<2>&, const NormalEstimationOptions&);
template int completeNormals<3>(const Points<3>&, Points<3>&, const NormalEstimationOptions&);
template double orientationDisagreement<2>(const Points<2>&, const Points<2>&, const NormalEstimationOptions&);
template double orientationDisagreement<3>(const Points<3>&, const Points<3>&, const NormalEstimationOptions&);
template int orientNormalLines<2>(const Points<2>&, Points<2>&, const NormalEstimationOptions&);
template int orientNormalLines<3>(const Points<3>&, Points<3>&, const NormalEstimationOptions&);

}  // namespace hermite
