#include "core/points/normal_estimation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
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
  Eigen::SelfAdjointEigenSolver<Mat<Dim>> eig(C);
  Vec<Dim> nrm = eig.eigenvectors().col(0);  // smallest eigenvalue first
  if (!(nrm.norm() > 0) || !nrm.allFinite()) nrm = Vec<Dim>::UnitX();
  return nrm.normalized();
}

// The normal of the hyperplane through pᵢ and its neighbours j (and l in 3D), or zero when they
// span no hyperplane.
template <int Dim>
Vec<Dim> planeNormal(const Vec<Dim>& a, const Vec<Dim>& b) {
  if constexpr (Dim == 2) {
    (void)b;
    return Vec<Dim>(-a.y(), a.x());
  } else {
    return a.cross(b);
  }
}

// Point i's normal, robust to a second sheet among its neighbours: of the hyperplanes through pᵢ
// and Dim − 1 of its neighbours, the one with the most neighbours within 0.3 × the neighbourhood
// radius of it (a sheet's own neighbours; another sheet a gap away is off it), then PCA over
// those. Plain PCA over all k when no hyperplane holds Dim + 1 of them or at least 2 more than
// PCA's own.
template <int Dim>
Vec<Dim> robustNormal(const Points<Dim>& points, const NeighbourGraph& g, int i, std::vector<std::uint32_t>& inliers) {
  const std::uint32_t* idx = g.of(i);
  const Vec<Dim> p = points.col(i);
  double radius = 0;
  for (int j = 0; j < g.k; ++j) radius = std::max(radius, (points.col(idx[j]) - p).norm());
  const double tol = 0.3 * radius;
  int best = 0;
  Vec<Dim> bestNormal = Vec<Dim>::Zero();
  for (int a = 0; a < g.k; ++a)
    for (int b = Dim == 2 ? a : a + 1; b < (Dim == 2 ? a + 1 : g.k); ++b) {
      Vec<Dim> n = planeNormal<Dim>(points.col(idx[a]) - p, points.col(idx[b]) - p);
      const double len = n.norm();
      if (!(len > 1e-12 * radius * radius)) continue;
      n /= len;
      int count = 0;
      for (int j = 0; j < g.k; ++j) count += std::abs(n.dot(points.col(idx[j]) - p)) <= tol;
      if (count > best) best = count, bestNormal = n;
    }
  // PCA's own hyperplane through pᵢ stands unless another holds clearly more neighbours (on a
  // curved sheet the chords' hyperplanes hold about as many, and PCA is the better estimate).
  const Vec<Dim> pca = pcaNormal<Dim>(points, idx, g.k);
  int pcaCount = 0;
  for (int j = 0; j < g.k; ++j) pcaCount += std::abs(pca.dot(points.col(idx[j]) - p)) <= tol;
  if (best < Dim + 1 || best < pcaCount + 2) return pca;
  inliers.clear();
  for (int j = 0; j < g.k; ++j)
    if (std::abs(bestNormal.dot(points.col(idx[j]) - p)) <= tol) inliers.push_back(idx[j]);
  return pcaNormal<Dim>(points, inliers.data(), static_cast<int>(inliers.size()));
}

// How an orientation crosses the edge i → j, and at what cost (see the header). `flip` says
// whether nⱼ as it stands must change sign to follow nᵢ as it stands (i is the oriented end):
//   along a sheet   d = pⱼ − pᵢ in both tangent planes, normals agree: copy (flip when
//                   nᵢ·nⱼ < 0), cost 1 − |nᵢ·nⱼ| < 1;
//   across a gap    d along both normals, normals parallel: the sheets of a closed surface face
//                   each other there (both away from or both toward the region between), so nⱼ
//                   takes the opposite orientation, cost 2 + (1 − |nᵢ·nⱼ|) + (1 − the smaller
//                   |d̂·n|);
//   any other edge  (a crease, a fold, noise), the last resort at cost 4 + (1 − its margin):
//                   where d leaves both tangent planes more steeply than the normals agree
//                   (min |d̂·n| > |nᵢ·nⱼ|, a sharp crease) by the crease rule — across a crease
//                   of a consistently oriented surface, convex or concave, d·nᵢ and d·nⱼ have
//                   opposite signs — with margin min |d̂·n|; else copy, margin |nᵢ·nⱼ|.
enum class EdgeKind { Along, Across, Crease, Other };

struct EdgeRule {
  double cost = 0;
  bool flip = false;
  EdgeKind kind = EdgeKind::Other;
};

template <int Dim>
EdgeRule edgeRule(const Points<Dim>& P, const Points<Dim>& N, int i, int j, const NormalEstimationOptions& o) {
  const Vec<Dim> ni = N.col(i).normalized(), nj = N.col(j).normalized();
  const double dot = ni.dot(nj), agree = std::abs(dot);
  const Vec<Dim> d = P.col(j) - P.col(i);
  const double len = d.norm();
  if (!(len > 0)) return {1.0 - agree, dot < 0, EdgeKind::Along};  // a duplicate point: the same sheet
  const double di = d.dot(ni) / len, dj = d.dot(nj) / len;
  const double li = std::abs(di), lj = std::abs(dj);
  if (agree >= o.agreeCosine && std::max(li, lj) <= o.gapSine) return {1.0 - agree, dot < 0, EdgeKind::Along};
  if (agree >= o.acrossCosine && std::min(li, lj) >= o.acrossCosine)
    return {2.0 + (1.0 - agree) + (1.0 - std::min(li, lj)), dot > 0, EdgeKind::Across};
  if (std::min(li, lj) > agree) return {4.0 + (1.0 - std::min(li, lj)), di * dj > 0, EdgeKind::Crease};
  return {4.0 + (1.0 - agree), dot < 0, EdgeKind::Other};
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

// Orients the normals of the points with `done[i]` == 0 (Prim's tree from the others, then from
// seeds); each tree edge passes the parent's orientation to the child by its EdgeRule. `part`
// (when given, N entries) receives each point's tree: −1 for the trees grown from the points
// already done, else the index of its seed in seeding order.
template <int Dim>
void orientNormals(const Points<Dim>& P, Points<Dim>& N, std::vector<char> done, const NeighbourGraph& g,
                   const NormalEstimationOptions& o, std::vector<int>* part = nullptr) {
  const int n = static_cast<int>(P.cols());
  struct Item {
    double cost;
    std::uint32_t child, parent;
    bool flip;  // the child's normal changes sign to follow its parent's (EdgeRule)
    bool operator>(const Item& o) const { return cost > o.cost; }
  };
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  auto push = [&](std::uint32_t from) {
    auto edge = [&](std::uint32_t to) {
      if (done[to]) return;
      const EdgeRule r = edgeRule<Dim>(P, N, int(from), int(to), o);
      heap.push({r.cost, to, from, r.flip});
    };
    for (int j = 0; j < g.k; ++j) edge(g.of(int(from))[j]);
    for (std::uint32_t to : g.reverse[from]) edge(to);
  };
  for (int i = 0; i < n; ++i)
    if (done[i]) push(static_cast<std::uint32_t>(i));
  std::vector<std::vector<int>> order(Dim, std::vector<int>(static_cast<std::size_t>(n)));
  for (int a = 0; a < Dim; ++a) {
    std::iota(order[a].begin(), order[a].end(), 0);
    std::sort(order[a].begin(), order[a].end(), [&](int x, int y) { return P(a, x) > P(a, y); });
  }
  std::vector<std::size_t> cursor(Dim, 0);
  if (part) part->assign(static_cast<std::size_t>(n), -1);
  for (int tree = 0;; ++tree) {
    while (!heap.empty()) {
      const Item e = heap.top();
      heap.pop();
      if (done[e.child]) continue;
      done[e.child] = 1;
      if (e.flip) N.col(e.child) = -N.col(e.child);
      if (part) (*part)[e.child] = (*part)[e.parent];
      push(e.child);
    }
    int axis = 0;
    const int seed = nextSeed<Dim>(N, done, order, cursor, axis);
    if (seed < 0) return;
    if (N(axis, seed) < 0) N.col(seed) = -N.col(seed);
    done[seed] = 1;
    if (part) (*part)[seed] = tree;
    push(static_cast<std::uint32_t>(seed));
  }
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
#pragma omp parallel
  {
    std::vector<std::uint32_t> inliers;
#pragma omp for schedule(dynamic, 1024)
    for (int i = 0; i < n; ++i)
      if (!known[i]) normals.col(i) = robustNormal<Dim>(points, g, i, inliers);
  }
  orientNormals<Dim>(points, normals, std::move(known), g, options);
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
        const EdgeRule r = edgeRule<Dim>(points, normals, i, o, options);
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
  std::vector<int> part;
  orientNormals<Dim>(points, normals, std::vector<char>(static_cast<std::size_t>(n), 0), g, options, &part);
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
