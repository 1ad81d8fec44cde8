#include "core/points/normal_orientation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <queue>
#include <utility>

namespace hermite::detail {

template <int Dim>
EdgeRule edgeRule(const Points<Dim>& P, const Points<Dim>& N, int i, int j, const NormalEstimationOptions& o,
                  double bandI, double bandJ, const Vec<Dim>& secondI, const Vec<Dim>& secondJ,
                  bool trusted) {
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

namespace {

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

}  // namespace

template <int Dim>
void orientNormals(const Points<Dim>& P, Points<Dim>& N, std::vector<char> done, const NeighbourGraph& g,
                   const std::vector<double>& band, const Points<Dim>& second, const NormalEstimationOptions& o,
                   std::vector<int>* part, const std::vector<char>* untrusted) {
  const int n = static_cast<int>(P.cols());
  std::vector<char> trusted = agreesWithNeighbours<Dim>(N, g);
  if (untrusted)
    for (int i = 0; i < n; ++i) trusted[i] = trusted[i] && !(*untrusted)[i];
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

template EdgeRule edgeRule<2>(const Points<2>&, const Points<2>&, int, int, const NormalEstimationOptions&, double,
                              double, const Vec<2>&, const Vec<2>&, bool);
template EdgeRule edgeRule<3>(const Points<3>&, const Points<3>&, int, int, const NormalEstimationOptions&, double,
                              double, const Vec<3>&, const Vec<3>&, bool);
template void orientNormals<2>(const Points<2>&, Points<2>&, std::vector<char>, const NeighbourGraph&,
                               const std::vector<double>&, const Points<2>&, const NormalEstimationOptions&,
                               std::vector<int>*, const std::vector<char>*);
template void orientNormals<3>(const Points<3>&, Points<3>&, std::vector<char>, const NeighbourGraph&,
                               const std::vector<double>&, const Points<3>&, const NormalEstimationOptions&,
                               std::vector<int>*, const std::vector<char>*);
template void followGivenMajority<2>(Points<2>&, const Points<2>&, const std::vector<int>&);
template void followGivenMajority<3>(Points<3>&, const Points<3>&, const std::vector<int>&);

}  // namespace hermite::detail
