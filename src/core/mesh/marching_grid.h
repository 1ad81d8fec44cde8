#pragma once
// Internal to marching_squares.cpp / marching_cubes.cpp: the sampled grid and the vertices on its
// sign-changing edges, shared by both dimensions.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "core/base/radix_sort.h"
#include "core/mesh/grid_lines.h"
#include "core/mesh/illinois_bracket.h"
#include "core/mesh/marching_cull.h"
#include "core/mesh/marching_memory.h"
#include "core/mesh/marching_options.h"

namespace hermite::detail {

template <int Dim>
struct MarchingGrid {
  GridLines<Dim> lines;                // the whole grid's lines per axis (world coordinates)
  // The uniform grid's cell size per axis (refined cells are smaller): its diagonal is the
  // margin by which validNear widens the data's reach.
  Vec<Dim> h;
  std::array<int, Dim> n{};            // cells per axis
  std::array<std::int64_t, Dim> stride{};  // point-index step per axis (points: n + 1 per axis)
  // Cells of the whole grid before this one's first, per axis: a slab of a streamed grid
  // (marching_slab.h) indexes its points locally and places them as the whole grid does.
  std::array<int, Dim> origin{};
  std::int64_t pointCount = 0;
  Eigen::VectorXd values;              // f at every grid point
  // valid[p] = 0: grid point p has no data (ImplicitField::valid, asked by markUsable where it
  // matters); empty when every point is valid. Edges and cells touching such a point get no
  // vertex and no geometry.
  std::vector<char> valid;

  // Sign-changing grid edges, key = pointIndex · Dim + axis (from the point to its +axis
  // neighbour), sorted; vertex v of the contour sits on edge edgeKeys[v].
  std::vector<std::int64_t> edgeKeys;
  Points<Dim> vertices;  // Dim × edgeKeys.size(), refined positions
  Points<Dim> gradients; // ∇f at the final positions
  // vertexValid[v] = 0: vertex v, a point of the zero set, has no data
  // (ImplicitField::validOnZeroSet); empty when the field is valid everywhere. A polygon
  // (segment) whose vertices all have no data is left out; each is decided once, so the contour
  // stays manifold.
  std::vector<char> vertexValid;

  std::array<int, Dim> coords(std::int64_t idx) const {
    std::array<int, Dim> c{};
    for (int a = Dim - 1; a >= 0; --a) {
      c[a] = static_cast<int>(idx / stride[a]);
      idx -= c[a] * stride[a];
    }
    return c;
  }
  Vec<Dim> point(std::int64_t idx) const {
    const std::array<int, Dim> c = coords(idx);
    Vec<Dim> x;
    for (int a = 0; a < Dim; ++a) x[a] = lines[a][static_cast<size_t>(c[a] + origin[a])];
    return x;
  }
  // The length of cell c (local) along axis a.
  double step(int a, int c) const {
    const size_t i = static_cast<size_t>(c + origin[a]);
    return lines[a][i + 1] - lines[a][i];
  }
  bool inside(std::int64_t idx) const { return values[idx] < 0; }
  bool isValid(std::int64_t idx) const { return valid.empty() || valid[static_cast<size_t>(idx)]; }
  bool isVertexValid(int v) const { return vertexValid.empty() || vertexValid[static_cast<size_t>(v)]; }
  // The contour vertex on the edge from point idx along axis, or -1.
  int vertexOn(std::int64_t idx, int axis) const {
    const std::int64_t key = idx * Dim + axis;
    const auto it = std::lower_bound(edgeKeys.begin(), edgeKeys.end(), key);
    return it != edgeKeys.end() && *it == key ? static_cast<int>(it - edgeKeys.begin()) : -1;
  }
};

// The columns of X in Morton (Z-curve) order of their position quantised to 2¹⁰ steps per axis
// over X's bounding box: consecutive entries lie close together, so a field that shares work
// between neighbouring points in a batch (a partition of unity) meets few supports per run.
template <int Dim>
std::vector<Eigen::Index> spatialOrder(const Points<Dim>& X) {
  const Eigen::Index n = X.cols();
  std::vector<Eigen::Index> order(static_cast<size_t>(n));
  if (n == 0) return order;
  const Vec<Dim> lo = X.rowwise().minCoeff(), ext = X.rowwise().maxCoeff() - lo;
  std::vector<std::pair<std::uint64_t, Eigen::Index>> keys(static_cast<size_t>(n));
#pragma omp parallel for schedule(static)
  for (Eigen::Index i = 0; i < n; ++i) {
    std::uint64_t key = 0;
    for (int a = 0; a < Dim; ++a) {
      const double t = ext[a] > 0 ? (X(a, i) - lo[a]) / ext[a] : 0.0;
      const auto q = static_cast<std::uint64_t>(std::clamp(t, 0.0, 1.0) * 1023.0);
      for (int bit = 0; bit < 10; ++bit) key |= ((q >> bit) & 1u) << (bit * Dim + a);
    }
    keys[static_cast<size_t>(i)] = {key, i};
  }
  radixSort(keys);  // (key, column): a strict total order
  for (Eigen::Index i = 0; i < n; ++i) order[static_cast<size_t>(i)] = keys[static_cast<size_t>(i)].second;
  return order;
}

// f and ∇f at the columns of X in chunks of 2¹⁴ points in spatialOrder (each f(i) depends on
// X.col(i) alone, so the order changes only the speed), polling `cancel` between them.
template <int Dim>
void evaluateChunked(const ImplicitField<Dim>& field, const Points<Dim>& X, Eigen::VectorXd& f, Points<Dim>& G,
                     const CancelToken* cancel) {
  constexpr Eigen::Index kChunk = 1 << 14;
  const Eigen::Index n = X.cols();
  f.resize(n);
  G.resize(Dim, n);
  const std::vector<Eigen::Index> order = spatialOrder(X);
  Eigen::VectorXd fc;
  Points<Dim> Xc, Gc;
  for (Eigen::Index begin = 0; begin < n; begin += kChunk) {
    throwIfCancelled(cancel);
    const Eigen::Index count = std::min(kChunk, n - begin);
    Xc.resize(Dim, count);
    for (Eigen::Index i = 0; i < count; ++i) Xc.col(i) = X.col(order[static_cast<size_t>(begin + i)]);
    field.evaluateBatch(Xc, fc, &Gc);
    for (Eigen::Index i = 0; i < count; ++i) {
      f[order[static_cast<size_t>(begin + i)]] = fc[i];
      G.col(order[static_cast<size_t>(begin + i)]) = Gc.col(i);
    }
  }
}

// A 3-wide maximum of `mask` along each axis in turn: afterwards mask[p] is set when a point
// within one grid step of p on every axis (Chebyshev distance 1) was set.
template <int Dim>
void dilateMask(const MarchingGrid<Dim>& g, std::vector<char>& mask) {
  std::vector<char> next(mask.size());
  for (int a = 0; a < Dim; ++a) {
    const std::int64_t step = g.stride[a];
#pragma omp parallel for schedule(static)
    for (std::int64_t p = 0; p < g.pointCount; ++p) {
      const int c = g.coords(p)[a];
      char v = mask[static_cast<size_t>(p)];
      if (c > 0) v |= mask[static_cast<size_t>(p - step)];
      if (c < g.n[a]) v |= mask[static_cast<size_t>(p + step)];
      next[static_cast<size_t>(p)] = v;
    }
    mask.swap(next);
  }
}

// g.valid for a field that may have no data (ImplicitField::valid): asked only where it can
// matter, at the grid points within one step (Chebyshev) of an end of a sign-changing edge — the
// corners of every sign-changing cell. Other points count as without data: their cells have no
// sign change and make no geometry whatever their validity.
template <int Dim>
void markUsable(MarchingGrid<Dim>& g, const ImplicitField<Dim>& field, const CancelToken* cancel) {
  std::vector<char> mask(static_cast<size_t>(g.pointCount), 0);
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < g.pointCount; ++p) {
    const std::array<int, Dim> c = g.coords(p);
    for (int a = 0; a < Dim; ++a) {
      if (c[a] > 0 && g.inside(p) != g.inside(p - g.stride[a])) mask[static_cast<size_t>(p)] = 1;
      if (c[a] < g.n[a] && g.inside(p) != g.inside(p + g.stride[a])) mask[static_cast<size_t>(p)] = 1;
    }
  }
  dilateMask(g, mask);
  g.valid.assign(static_cast<size_t>(g.pointCount), 0);
  constexpr std::size_t kChunk = 1 << 14;
  std::vector<std::int64_t> todo;
  Points<Dim> X;
  std::vector<char> ok;
  auto flush = [&] {
    throwIfCancelled(cancel);
    X.resize(Dim, static_cast<Eigen::Index>(todo.size()));
    for (size_t i = 0; i < todo.size(); ++i) X.col(static_cast<Eigen::Index>(i)) = g.point(todo[i]);
    field.validBatch(X, ok, g.h.norm());
    for (size_t i = 0; i < todo.size(); ++i) g.valid[static_cast<size_t>(todo[i])] = ok[i];
    todo.clear();
  };
  for (std::int64_t p = 0; p < g.pointCount; ++p) {
    if (!mask[static_cast<size_t>(p)]) continue;
    todo.push_back(p);
    if (todo.size() == kChunk) flush();
  }
  if (!todo.empty()) flush();
}

// InputError for a resolution outside [1, 4096] or a box that is not finite with min < max.
template <int Dim>
void checkMarchingInput(const Box<Dim>& box, int resolution) {
  if (resolution < 1 || resolution > 4096)
    throw InputError("marching: resolution must be in [1, 4096], got " + std::to_string(resolution));
  const Vec<Dim> ext = box.extent();
  if (!ext.allFinite() || !(ext.minCoeff() > 0) || !box.lo.allFinite())
    throw InputError("marching: the box must be finite with min < max on every axis");
}

// The uniform grid's cell size per axis over the box (world units), after checkMarchingInput.
template <int Dim>
Vec<Dim> marchingCellSize(const Box<Dim>& box, int resolution) {
  checkMarchingInput<Dim>(box, resolution);
  const auto n = marchingCells<Dim>(box, resolution);
  Vec<Dim> h;
  for (int a = 0; a < Dim; ++a) h[a] = box.extent()[a] / n[a];
  return h;
}

// The uniform grid's lines over the box, after checkMarchingInput.
template <int Dim>
GridLines<Dim> marchingLines(const Box<Dim>& box, int resolution) {
  checkMarchingInput<Dim>(box, resolution);
  return uniformGridLines<Dim>(box, marchingCells<Dim>(box, resolution));
}

// The grid over `lines` (h: the uniform grid's cell size they refine) and f at every grid point
// (batched to bound memory).
template <int Dim>
MarchingGrid<Dim> sampleGrid(const ImplicitField<Dim>& field, const GridLines<Dim>& lines, const Vec<Dim>& h,
                             const MarchingOptions& options, MarchingReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  MarchingGrid<Dim> g;
  g.lines = lines;
  g.h = h;
  g.n = gridCells<Dim>(lines);
  checkMemory(marchingGridPlan<Dim>(g.n, options.resolution), kMarchingRemedy);
  std::int64_t s = 1;
  for (int a = 0; a < Dim; ++a) {
    g.stride[a] = s;
    s *= g.n[a] + 1;
  }
  g.pointCount = s;
  g.values.resize(s);
  // needed[p]: f must be evaluated at grid point p (all of them without culling).
  std::vector<char> needed;
  if (options.cull) needed = cullBlocks(g, field, options.cancel);
  else needed.assign(static_cast<size_t>(s), 1);
  // Evaluated in batches of up to 2¹⁴ points (bounded memory whatever the resolution; cancel and
  // progress between batches).
  std::int64_t total = 0;
  std::vector<std::int64_t> todo;
  Points<Dim> X;
  Eigen::VectorXd f;
  auto flush = [&] {
    X.resize(Dim, static_cast<Eigen::Index>(todo.size()));
    for (size_t i = 0; i < todo.size(); ++i) X.col(static_cast<Eigen::Index>(i)) = g.point(todo[i]);
    field.evaluateBatch(X, f);
    for (size_t i = 0; i < todo.size(); ++i) {
      if (!std::isfinite(f[static_cast<Eigen::Index>(i)])) {
        std::string where;
        for (int a = 0; a < Dim; ++a) where += (a ? ", " : "") + std::to_string(X(a, static_cast<Eigen::Index>(i)));
        throw NumericalError("marching: f is not finite at grid point (" + where + ")");
      }
      g.values[todo[i]] = f[static_cast<Eigen::Index>(i)];
    }
    total += static_cast<std::int64_t>(todo.size());
    todo.clear();
  };
  std::int64_t neededCount = 0;
  for (char c : needed) neededCount += c;
  for (std::int64_t p = 0; p < s; ++p) {
    if (!needed[static_cast<size_t>(p)]) continue;
    todo.push_back(p);
    if (todo.size() == (1u << 14)) {
      throwIfCancelled(options.cancel);
      flush();
      if (options.progress) options.progress(double(total) / double(std::max<std::int64_t>(neededCount, 1)));
    }
  }
  throwIfCancelled(options.cancel);
  if (!todo.empty()) flush();
  if (options.progress) options.progress(1.0);
  if (!field.everywhereValid()) markUsable(g, field, options.cancel);
  if (report) {
    report->gridPoints = s;
    report->evaluatedPoints = total;
  }
  if (report) {
    for (int a = 0; a < Dim; ++a) report->cells[a] = g.n[a];
    report->evaluateMs = msSince(t0);
  }
  return g;
}

// g.edgeKeys: the sign-changing edges of the whole grid whose ends both have data, sorted.
template <int Dim>
void findEdges(MarchingGrid<Dim>& g) {
  const int slabs = g.n[Dim - 1] + 1;
  std::vector<std::vector<std::int64_t>> perSlab(static_cast<size_t>(slabs));
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < slabs; ++k) {
    std::vector<std::int64_t>& out = perSlab[static_cast<size_t>(k)];
    const std::int64_t begin = k * g.stride[Dim - 1], end = begin + g.stride[Dim - 1];
    for (std::int64_t p = begin; p < end; ++p) {
      const std::array<int, Dim> c = g.coords(p);
      for (int a = 0; a < Dim; ++a)
        if (c[a] < g.n[a] && g.inside(p) != g.inside(p + g.stride[a]) && g.isValid(p) && g.isValid(p + g.stride[a]))
          out.push_back(p * Dim + a);
    }
  }
  g.edgeKeys.clear();
  for (const auto& v : perSlab) g.edgeKeys.insert(g.edgeKeys.end(), v.begin(), v.end());
}

// Past MarchingOptions::newtonSteps, a vertex whose next step would still move it by more than
// kEdgeFinish of its edge goes on, for at most kEdgeFinishSteps more steps: an edge on which f
// bends sharply (the tip of a fin thinner than the sample spacing) converges slowly, and 4 steps
// left such vertices up to a quarter of a sample spacing off f = 0 on the Stanford dragon. A
// vertex also stops once its bracket is narrower than kEdgeBracket of the edge, or it is pinned
// at τ: where f jumps (a partition of unity's blend switching supports: thousands of vertices on
// CGAL's boeing) there is no root to converge to, only the jump to bracket. The rest are few, so
// the extra batches cost little.
inline constexpr double kEdgeFinish = 1e-6;
inline constexpr int kEdgeFinishSteps = 40;
inline constexpr double kEdgeBracket = 1e-4;  // a bracket this narrow (of the edge) is the vertex

// Places the vertices of g.edgeKeys (g.vertices, g.gradients): linear interpolation, then
// safeguarded Newton along the edge (bracketed by the end signs, false position when a step
// leaves the bracket, kept in [τ, 1 − τ]). Returns max |f| over the vertices after refinement.
template <int Dim>
double refineEdgeVertices(MarchingGrid<Dim>& g, const ImplicitField<Dim>& field, const MarchingOptions& options) {
  constexpr double tau = 1e-3;
  const int V = static_cast<int>(g.edgeKeys.size());
  Eigen::VectorXd t(V), tLo(V), tHi(V), fLo(V), fHi(V);  // parameter along the edge, its bracket and f there
  Eigen::VectorXd length(V);                                // the edge's length
  std::vector<std::int64_t> from(static_cast<size_t>(V));
  std::vector<int> axis(static_cast<size_t>(V));
  std::vector<signed char> lastMoved(static_cast<size_t>(V), 0);
  for (int v = 0; v < V; ++v) {
    from[v] = g.edgeKeys[v] / Dim;
    axis[v] = static_cast<int>(g.edgeKeys[v] % Dim);
    length[v] = g.step(axis[v], g.coords(from[v])[axis[v]]);
    const double fa = g.values[from[v]], fb = g.values[from[v] + g.stride[axis[v]]];
    t[v] = std::clamp(fa / (fa - fb), tau, 1 - tau);
    tLo[v] = 0;
    tHi[v] = 1;
    fLo[v] = fa;
    fHi[v] = fb;
  }
  auto position = [&](int v) {
    Vec<Dim> x = g.point(from[v]);
    x[axis[v]] += t[v] * length[v];
    return x;
  };
  Eigen::VectorXd f;
  Points<Dim> G;
  g.vertices.resize(Dim, V);
  for (int v = 0; v < V; ++v) g.vertices.col(v) = position(v);
  evaluateChunked(field, g.vertices, f, G, options.cancel);
  // Only vertices not yet converged (Newton step above 1e-9 of a cell) are iterated and
  // re-evaluated: for RBF fields each evaluation with ∇f is the expensive part.
  std::vector<int> active(static_cast<size_t>(V));
  for (int v = 0; v < V; ++v) active[static_cast<size_t>(v)] = v;
  std::vector<int> next;
  Points<Dim> X;
  Eigen::VectorXd fa;
  Points<Dim> Ga;
  const int lastStep = options.newtonSteps > 0 ? options.newtonSteps + kEdgeFinishSteps : 0;
  for (int step = 0; step < lastStep && !active.empty(); ++step) {
    throwIfCancelled(options.cancel);
    next.clear();
    for (int v : active) {
      const double slope = G(axis[v], v) * length[v];  // df/dt
      if (std::abs(f[v]) <= 1e-9 * std::abs(slope)) continue;  // converged
      if (step >= options.newtonSteps && (std::abs(f[v]) <= kEdgeFinish * std::abs(slope) ||
                                          tHi[v] - tLo[v] <= kEdgeBracket || t[v] == tau || t[v] == 1 - tau))
        continue;  // close enough, or f jumps in a tiny bracket, or the root is within τ of an end
      // Keep the bracket on the sign change (the end at t = 0 has values[from]'s sign); Illinois
      // keeps false position superlinear on the near-tangent edges where Newton overshoots.
      illinoisUpdate(tLo[v], fLo[v], tHi[v], fHi[v], lastMoved[v], t[v], f[v]);
      double tn = t[v] - f[v] / slope;
      // Outside the bracket: false position on it instead (never worse than the bracket).
      if (!std::isfinite(tn) || tn <= tLo[v] || tn >= tHi[v])
        tn = tLo[v] + (tHi[v] - tLo[v]) * fLo[v] / (fLo[v] - fHi[v]);
      tn = std::clamp(tn, tau, 1 - tau);
      if (tn == t[v]) continue;  // pinned at τ: nothing to evaluate again
      t[v] = tn;
      next.push_back(v);
    }
    X.resize(Dim, static_cast<Eigen::Index>(next.size()));
    for (size_t k = 0; k < next.size(); ++k) X.col(static_cast<Eigen::Index>(k)) = position(next[k]);
    evaluateChunked(field, X, fa, Ga, options.cancel);
    for (size_t k = 0; k < next.size(); ++k) {
      const int v = next[k];
      g.vertices.col(v) = X.col(static_cast<Eigen::Index>(k));
      f[v] = fa[static_cast<Eigen::Index>(k)];
      G.col(v) = Ga.col(static_cast<Eigen::Index>(k));
    }
    active.swap(next);
  }
  g.gradients = G;
  return V > 0 ? f.cwiseAbs().maxCoeff() : 0.0;
}

// g.vertexValid for a field that may have no data: validOnZeroSet at the refined vertices.
template <int Dim>
void markVertexValidity(MarchingGrid<Dim>& g, const ImplicitField<Dim>& field, const CancelToken* cancel) {
  g.vertexValid.clear();
  if (field.everywhereValid()) return;
  throwIfCancelled(cancel);
  field.validOnZeroSetBatch(g.vertices, g.vertexValid);
}

// findEdges, then refineEdgeVertices (report->maxAbsF) and markVertexValidity.
template <int Dim>
void placeEdgeVertices(MarchingGrid<Dim>& g, const ImplicitField<Dim>& field, const MarchingOptions& options,
                       MarchingReport* report) {
  findEdges(g);
  const double maxAbsF = refineEdgeVertices(g, field, options);
  if (report) report->maxAbsF = maxAbsF;
  markVertexValidity(g, field, options.cancel);
}

}  // namespace hermite::detail
