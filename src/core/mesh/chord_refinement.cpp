#include "core/mesh/chord_refinement.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "core/base/ms_since.h"
#include "core/base/radix_sort.h"
#include "core/mesh/marching_grid.h"

namespace hermite {

namespace {

// The mesh's undirected edges: per triangle corner k (edge from corner k to k + 1) the edge's
// index, and per edge its two vertices (lower index first).
struct EdgeTable {
  std::vector<int> ofCorner;            // 3·T
  std::vector<std::array<int, 2>> ends;  // E
};

EdgeTable buildEdges(const TriMesh& mesh) {
  const int T = mesh.triangleCount();
  std::vector<std::pair<std::uint64_t, int>> keyed(static_cast<std::size_t>(3) * T);
#pragma omp parallel for schedule(static)
  for (int t = 0; t < T; ++t)
    for (int k = 0; k < 3; ++k)
      keyed[3 * std::size_t(t) + k] = {edgeKey(mesh.triangles(k, t), mesh.triangles((k + 1) % 3, t)), 3 * t + k};
  radixSort(keyed);  // (edge, corner): a strict total order
  EdgeTable table;
  table.ofCorner.resize(keyed.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    if (i == 0 || keyed[i].first != keyed[i - 1].first)
      table.ends.push_back({static_cast<int>(keyed[i].first >> 32), static_cast<int>(keyed[i].first & 0xffffffffu)});
    table.ofCorner[static_cast<std::size_t>(keyed[i].second)] = static_cast<int>(table.ends.size()) - 1;
  }
  return table;
}

// Newton projection of the columns of X onto f = 0 along ∇f (chord_refinement.h); `chordMid` are
// the chord midpoints, `reach` half the edge lengths. Returns per column whether its projection
// succeeded; a failed one's edge is not split (its chord midpoint may lie far from the surface
// where the end normals differ most, and would become a vertex).
std::vector<char> projectOntoZeroSet(const ImplicitField<3>& field, Points<3>& X, Points<3>& normals,
                                     const Points<3>& chordMid, const Eigen::VectorXd& reach,
                                     const ChordRefinementOptions& options, ChordRefinementReport& report) {
  const Eigen::Index n = X.cols();
  Eigen::VectorXd f;
  Points<3> G;
  std::vector<Eigen::Index> active(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) active[static_cast<std::size_t>(i)] = i;
  Eigen::VectorXd fa;
  Points<3> Xa, Ga;
  std::vector<char> failed(static_cast<std::size_t>(n), 0);
  Eigen::VectorXd lastF = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
  Eigen::VectorXd lastDist = lastF;  // |f|/‖∇f‖: the first-order distance to f = 0
  for (int step = 0; step <= options.newtonSteps && !active.empty(); ++step) {
    Xa.resize(3, static_cast<Eigen::Index>(active.size()));
    for (std::size_t k = 0; k < active.size(); ++k) Xa.col(Eigen::Index(k)) = X.col(active[k]);
    detail::evaluateChunked<3>(field, Xa, fa, Ga, options.cancel);
    std::vector<Eigen::Index> next;
    for (std::size_t k = 0; k < active.size(); ++k) {
      const Eigen::Index i = active[k];
      const double fi = fa[Eigen::Index(k)];
      const Vec<3> g = Ga.col(Eigen::Index(k));
      const double g2 = g.squaredNorm();
      if (!std::isfinite(fi) || !(g2 > 0) || !std::isfinite(g2)) {
        failed[static_cast<std::size_t>(i)] = 1;
        continue;
      }
      normals.col(i) = g / std::sqrt(g2);
      lastF[i] = fi;
      lastDist[i] = std::abs(fi) / std::sqrt(g2);
      // Converged: within 10⁻⁴ of half the edge (far below any chord stray worth a split).
      if (std::abs(fi) <= 1e-4 * std::sqrt(g2) * reach[i] || step == options.newtonSteps) continue;
      const Vec<3> x = X.col(i) - (fi / g2) * g;
      if (!((x - chordMid.col(i)).norm() <= reach[i])) {
        failed[static_cast<std::size_t>(i)] = 1;
        continue;
      }
      X.col(i) = x;
      next.push_back(i);
    }
    active.swap(next);
  }
  std::vector<char> ok(static_cast<std::size_t>(n), 0);
  for (Eigen::Index i = 0; i < n; ++i) {
    // Converged well inside the edge's scale; otherwise the edge stays whole.
    if (failed[static_cast<std::size_t>(i)] || !(lastDist[i] <= 1e-3 * reach[i])) {
      ++report.unsplitEdges;
    } else {
      ok[static_cast<std::size_t>(i)] = 1;
      report.maxAbsF = std::max(report.maxAbsF, std::abs(lastF[i]));
    }
  }
  return ok;
}

// Leaves whole (ok = 0) the edges whose projected vertex (a column of X) `rejects`.
void rejectStrays(const Points<3>& X, const std::function<std::vector<char>(const Points<3>&)>& rejects,
                  std::vector<char>& ok, ChordRefinementReport& report) {
  std::vector<Eigen::Index> projected;
  for (std::size_t k = 0; k < ok.size(); ++k)
    if (ok[k]) projected.push_back(static_cast<Eigen::Index>(k));
  const std::vector<char> rejected = rejects(X(Eigen::all, projected));
  for (std::size_t i = 0; i < projected.size(); ++i)
    if (rejected[i]) {
      ok[static_cast<std::size_t>(projected[i])] = 0;
      ++report.rejectedEdges;
      ++report.unsplitEdges;
    }
}

// Appends the triangles of triangle (a, b, c) (counter-clockwise) with new vertices m[k] on its
// edge from corner k to k + 1 (−1: not split).
void splitTriangle(const std::array<int, 3>& v, const std::array<int, 3>& m, const Eigen::Matrix3Xd& X,
                   std::vector<std::array<int, 3>>& out) {
  const int splits = (m[0] >= 0) + (m[1] >= 0) + (m[2] >= 0);
  if (splits == 0) return out.push_back(v);
  if (splits == 3) {
    out.push_back({v[0], m[0], m[2]});
    out.push_back({m[0], v[1], m[1]});
    out.push_back({m[2], m[1], v[2]});
    out.push_back({m[0], m[1], m[2]});
    return;
  }
  // Rotate so that edge 0 is split (and, with two splits, edge 1 too).
  int r = 0;
  for (; r < 3; ++r) {
    const bool first = m[r] >= 0, second = m[(r + 1) % 3] >= 0;
    if (splits == 1 ? first : (first && second)) break;
  }
  const int a = v[r], b = v[(r + 1) % 3], c = v[(r + 2) % 3];
  const int m0 = m[r], m1 = m[(r + 1) % 3];
  if (splits == 1) {
    out.push_back({a, m0, c});
    out.push_back({m0, b, c});
    return;
  }
  out.push_back({m0, b, m1});
  // The quad a, m0, m1, c by its shorter diagonal.
  if ((X.col(m0) - X.col(c)).squaredNorm() <= (X.col(a) - X.col(m1)).squaredNorm()) {
    out.push_back({a, m0, c});
    out.push_back({m0, m1, c});
  } else {
    out.push_back({a, m0, m1});
    out.push_back({a, m1, c});
  }
}

constexpr double kCos60 = 0.5;  // beyond 60° between the end normals the sagitta is no estimate

// The edges whose chord strays more than `tolerance` from the surface — sagitta (n_j − n_i)·(p_j − p_i)/8
// from the end normals — or whose end normals are more than 60° apart.
std::vector<int> candidateEdges(const TriMesh& mesh, const EdgeTable& edges, double tolerance) {
  std::vector<int> candidates;
  const int E = static_cast<int>(edges.ends.size());
  for (int e = 0; e < E; ++e) {
    const int i = edges.ends[e][0], j = edges.ends[e][1];
    const double s = (mesh.normals.col(j) - mesh.normals.col(i)).dot(mesh.vertices.col(j) - mesh.vertices.col(i)) / 8;
    if (std::abs(s) > tolerance || mesh.normals.col(i).dot(mesh.normals.col(j)) < kCos60) candidates.push_back(e);
  }
  return candidates;
}

// Per candidate edge (3 × C each): the start X (the chord's midpoint moved by the sagitta along the
// mean normal when the normals are within 60°), the chord's midpoint, the mean normal N, and the
// reach (half the chord) projectOntoZeroSet allows.
struct ChordStarts {
  Points<3> X, chordMid, N;
  Eigen::VectorXd reach;
};

ChordStarts chordStarts(const TriMesh& mesh, const EdgeTable& edges, const std::vector<int>& candidates) {
  const Eigen::Index C = static_cast<Eigen::Index>(candidates.size());
  ChordStarts c{Points<3>(3, C), Points<3>(3, C), Points<3>(3, C), Eigen::VectorXd(C)};
  for (Eigen::Index k = 0; k < C; ++k) {
    const int i = edges.ends[candidates[k]][0], j = edges.ends[candidates[k]][1];
    const Vec<3> pi = mesh.vertices.col(i), pj = mesh.vertices.col(j);
    const Vec<3> ni = mesh.normals.col(i), nj = mesh.normals.col(j);
    c.chordMid.col(k) = 0.5 * (pi + pj);
    c.reach[k] = 0.5 * (pj - pi).norm();
    const Vec<3> nSum = ni + nj;
    c.N.col(k) = nSum.norm() > 0 ? Vec<3>(nSum.normalized()) : ni;
    c.X.col(k) = c.chordMid.col(k);
    if (ni.dot(nj) >= kCos60) c.X.col(k) += ((nj - ni).dot(pj - pi) / 8) * c.N.col(k);
  }
  return c;
}

// The mesh with a new vertex (position X, normal N) on every candidate edge that projected (`ok`),
// appended after the old vertices in candidate order, and every triangle split at its new vertices.
TriMesh splitEdges(const TriMesh& mesh, const EdgeTable& edges, const std::vector<int>& candidates,
                   const ChordStarts& c, const std::vector<char>& ok) {
  const int V = mesh.vertexCount();
  std::vector<int> newVertex(edges.ends.size(), -1);
  std::vector<Eigen::Index> kept;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    if (ok[k]) {
      newVertex[static_cast<std::size_t>(candidates[k])] = V + static_cast<int>(kept.size());
      kept.push_back(static_cast<Eigen::Index>(k));
    }
  const Eigen::Index S = static_cast<Eigen::Index>(kept.size());
  TriMesh out;
  out.vertices.resize(3, V + S);
  out.vertices.leftCols(V) = mesh.vertices;
  out.normals.resize(3, V + S);
  out.normals.leftCols(V) = mesh.normals;
  for (Eigen::Index k = 0; k < S; ++k) {
    out.vertices.col(V + k) = c.X.col(kept[static_cast<std::size_t>(k)]);
    out.normals.col(V + k) = c.N.col(kept[static_cast<std::size_t>(k)]);
  }
  std::vector<std::array<int, 3>> tris;
  tris.reserve(static_cast<std::size_t>(mesh.triangleCount()) + 3 * static_cast<std::size_t>(S));
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    std::array<int, 3> v{}, m{};
    for (int k = 0; k < 3; ++k) {
      v[k] = mesh.triangles(k, t);
      m[k] = newVertex[static_cast<std::size_t>(edges.ofCorner[3 * std::size_t(t) + k])];
    }
    splitTriangle(v, m, out.vertices, tris);
  }
  out.triangles.resize(3, static_cast<Eigen::Index>(tris.size()));
  for (std::size_t t = 0; t < tris.size(); ++t)
    for (int k = 0; k < 3; ++k) out.triangles(k, Eigen::Index(t)) = tris[t][k];
  return out;
}

}  // namespace

TriMesh refineChords(const TriMesh& mesh, const ImplicitField<3>& field, const ChordRefinementOptions& options,
                     ChordRefinementReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  ChordRefinementReport local;
  ChordRefinementReport& r = report ? *report : local;
  r = ChordRefinementReport{};
  if (!mesh.hasNormals() || mesh.triangleCount() == 0 || !(options.tolerance > 0)) return mesh;
  const EdgeTable edges = buildEdges(mesh);
  const std::vector<int> candidates = candidateEdges(mesh, edges, options.tolerance);
  ChordStarts starts = chordStarts(mesh, edges, candidates);
  std::vector<char> ok = projectOntoZeroSet(field, starts.X, starts.N, starts.chordMid, starts.reach, options, r);
  if (options.rejects) rejectStrays(starts.X, options.rejects, ok, r);
  TriMesh out = splitEdges(mesh, edges, candidates, starts, ok);
  r.splitEdges = out.vertexCount() - mesh.vertexCount();
  r.ms = msSince(t0);
  return out;
}

}  // namespace hermite
