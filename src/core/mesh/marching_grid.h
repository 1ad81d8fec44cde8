#pragma once
// Internal to marching_squares.cpp / marching_cubes.cpp: the sampled grid and the vertices on its
// sign-changing edges, shared by both dimensions.

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/base/ms_since.h"
#include "core/mesh/marching_memory.h"
#include "core/mesh/marching_options.h"

namespace hermite::detail {

template <int Dim>
struct MarchingGrid {
  Vec<Dim> lo;
  Vec<Dim> h;                          // cell size per axis
  std::array<int, Dim> n{};            // cells per axis
  std::array<std::int64_t, Dim> stride{};  // point-index step per axis (points: n + 1 per axis)
  std::int64_t pointCount = 0;
  Eigen::VectorXd values;              // f at every grid point

  // Sign-changing grid edges, key = pointIndex · Dim + axis (from the point to its +axis
  // neighbour), sorted; vertex v of the contour sits on edge edgeKeys[v].
  std::vector<std::int64_t> edgeKeys;
  Points<Dim> vertices;  // Dim × edgeKeys.size(), refined positions
  Points<Dim> gradients; // ∇f at the final positions

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
    for (int a = 0; a < Dim; ++a) x[a] = lo[a] + h[a] * c[a];
    return x;
  }
  bool inside(std::int64_t idx) const { return values[idx] < 0; }
  // The contour vertex on the edge from point idx along axis, or -1.
  int vertexOn(std::int64_t idx, int axis) const {
    const std::int64_t key = idx * Dim + axis;
    const auto it = std::lower_bound(edgeKeys.begin(), edgeKeys.end(), key);
    return it != edgeKeys.end() && *it == key ? static_cast<int>(it - edgeKeys.begin()) : -1;
  }
};

// Culling (MarchingOptions::cull): fills g.values with a same-signed stand-in at the points of
// blocks that cannot contain the zero set and returns which points still need f.
template <int Dim>
std::vector<char> cullBlocks(MarchingGrid<Dim>& g, const ImplicitField<Dim>& field) {
  constexpr int B = 4, Super = 4;  // block: B cells per axis; super-block: Super blocks per axis
  std::array<int, Dim> nb{};
  std::int64_t blocks = 1;
  for (int a = 0; a < Dim; ++a) {
    nb[a] = (g.n[a] + B - 1) / B;
    blocks *= nb[a];
  }
  auto blockCoords = [&](std::int64_t b) {
    std::array<int, Dim> c{};
    for (int a = 0; a < Dim; ++a) {
      c[a] = static_cast<int>(b % nb[a]);
      b /= nb[a];
    }
    return c;
  };
  // Block b spans grid points [B·c, min(B·c + B, n)] per axis.
  auto blockBox = [&](const std::array<int, Dim>& c, int size) {
    Box<Dim> box;
    for (int a = 0; a < Dim; ++a) {
      box.lo[a] = g.lo[a] + g.h[a] * (B * c[a]);
      box.hi[a] = g.lo[a] + g.h[a] * std::min(B * (c[a] + size), g.n[a]);
    }
    return box;
  };
  Points<Dim> centres(Dim, blocks);
  Eigen::VectorXd radius(blocks), lipschitz(blocks);
  // One Lipschitz bound per super-block, valid for every block inside it.
  std::array<int, Dim> ns{};
  std::int64_t supers = 1;
  for (int a = 0; a < Dim; ++a) {
    ns[a] = (nb[a] + Super - 1) / Super;
    supers *= ns[a];
  }
  Eigen::VectorXd superL(supers);
#pragma omp parallel for schedule(dynamic, 4)
  for (std::int64_t sb = 0; sb < supers; ++sb) {
    std::array<int, Dim> c{};
    std::int64_t rest = sb;
    for (int a = 0; a < Dim; ++a) {
      c[a] = static_cast<int>(rest % ns[a]) * Super;
      rest /= ns[a];
    }
    superL[sb] = field.lipschitzBound(blockBox(c, Super));
  }
  for (std::int64_t b = 0; b < blocks; ++b) {
    const std::array<int, Dim> c = blockCoords(b);
    const Box<Dim> box = blockBox(c, 1);
    centres.col(b) = box.center();
    radius[b] = 0.5 * box.extent().norm();
    std::int64_t sb = 0, stride = 1;
    for (int a = 0; a < Dim; ++a) {
      sb += (c[a] / Super) * stride;
      stride *= ns[a];
    }
    lipschitz[b] = superL[sb];
  }
  Eigen::VectorXd fc;
  field.evaluateBatch(centres, fc);
  std::vector<char> needed(static_cast<size_t>(g.pointCount), 0);
  std::vector<char> culled(static_cast<size_t>(blocks), 0);
  for (std::int64_t b = 0; b < blocks; ++b) {
    const double margin = lipschitz[b] * radius[b] * (1 + 1e-9);
    culled[b] = std::isfinite(fc[b]) && std::isfinite(margin) && std::abs(fc[b]) > margin;
    if (culled[b]) continue;
    const std::array<int, Dim> c = blockCoords(b);
    std::array<int, Dim> lo{}, hi{};
    for (int a = 0; a < Dim; ++a) {
      lo[a] = B * c[a];
      hi[a] = std::min(B * c[a] + B, g.n[a]);
    }
    if constexpr (Dim == 2) {
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int i = lo[0]; i <= hi[0]; ++i) needed[static_cast<size_t>(i + g.stride[1] * j)] = 1;
    } else {
      for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int i = lo[0]; i <= hi[0]; ++i)
            needed[static_cast<size_t>(i + g.stride[1] * j + g.stride[2] * k)] = 1;
    }
  }
  // Points only in culled blocks: every block holding them is culled and has their true sign;
  // the stand-in |f(c)| − L·r is a lower bound of |f| there, with that sign.
  for (std::int64_t p = 0; p < g.pointCount; ++p) {
    if (needed[static_cast<size_t>(p)]) continue;
    const std::array<int, Dim> pc = g.coords(p);
    std::int64_t b = 0, stride = 1;
    for (int a = 0; a < Dim; ++a) {
      b += std::min(pc[a] / B, nb[a] - 1) * stride;
      stride *= nb[a];
    }
    const double bound = std::max(std::abs(fc[b]) - lipschitz[b] * radius[b], 1e-300);
    g.values[p] = fc[b] < 0 ? -bound : bound;
  }
  return needed;
}

// Grid layout and f at every grid point (batched by slabs of the last axis to bound memory).
template <int Dim>
MarchingGrid<Dim> sampleGrid(const ImplicitField<Dim>& field, const Box<Dim>& box, const MarchingOptions& options,
                             MarchingReport* report) {
  if (options.resolution < 1 || options.resolution > 4096)
    throw InputError("marching: resolution must be in [1, 4096], got " + std::to_string(options.resolution));
  const Vec<Dim> ext = box.extent();
  if (!ext.allFinite() || !(ext.minCoeff() > 0) || !box.lo.allFinite())
    throw InputError("marching: the box must be finite with min < max on every axis");
  const auto t0 = std::chrono::steady_clock::now();
  MarchingGrid<Dim> g;
  g.lo = box.lo;
  checkMemory(marchingGridPlan<Dim>(box, options.resolution), kMarchingRemedy);
  g.n = marchingCells<Dim>(box, options.resolution);
  std::int64_t s = 1;
  for (int a = 0; a < Dim; ++a) {
    g.h[a] = ext[a] / g.n[a];
    g.stride[a] = s;
    s *= g.n[a] + 1;
  }
  g.pointCount = s;
  g.values.resize(s);
  // needed[p]: f must be evaluated at grid point p (all of them without culling).
  std::vector<char> needed;
  if (options.cull) needed = cullBlocks(g, field);
  else needed.assign(static_cast<size_t>(s), 1);
  // Evaluated in batches of up to 2²⁰ points (bounded memory whatever the resolution).
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
  for (std::int64_t p = 0; p < s; ++p) {
    if (!needed[static_cast<size_t>(p)]) continue;
    todo.push_back(p);
    if (todo.size() == (1u << 20)) flush();
  }
  if (!todo.empty()) flush();
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

// Finds the sign-changing edges and places their vertices: linear interpolation, then
// safeguarded Newton along the edge (bracketed by the end signs, false position when a step
// leaves the bracket, kept in [τ, 1 − τ]).
template <int Dim>
void placeEdgeVertices(MarchingGrid<Dim>& g, const ImplicitField<Dim>& field, const MarchingOptions& options,
                       MarchingReport* report) {
  const int slabs = g.n[Dim - 1] + 1;
  std::vector<std::vector<std::int64_t>> perSlab(static_cast<size_t>(slabs));
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < slabs; ++k) {
    std::vector<std::int64_t>& out = perSlab[static_cast<size_t>(k)];
    const std::int64_t begin = k * g.stride[Dim - 1], end = begin + g.stride[Dim - 1];
    for (std::int64_t p = begin; p < end; ++p) {
      const std::array<int, Dim> c = g.coords(p);
      for (int a = 0; a < Dim; ++a)
        if (c[a] < g.n[a] && g.inside(p) != g.inside(p + g.stride[a])) out.push_back(p * Dim + a);
    }
  }
  g.edgeKeys.clear();
  for (const auto& v : perSlab) g.edgeKeys.insert(g.edgeKeys.end(), v.begin(), v.end());

  constexpr double tau = 1e-3;
  const int V = static_cast<int>(g.edgeKeys.size());
  Eigen::VectorXd t(V), tLo(V), tHi(V), fLo(V), fHi(V);  // parameter along the edge, its bracket and f there
  std::vector<std::int64_t> from(static_cast<size_t>(V));
  std::vector<int> axis(static_cast<size_t>(V));
  std::vector<signed char> lastMoved(static_cast<size_t>(V), 0);
  for (int v = 0; v < V; ++v) {
    from[v] = g.edgeKeys[v] / Dim;
    axis[v] = static_cast<int>(g.edgeKeys[v] % Dim);
    const double fa = g.values[from[v]], fb = g.values[from[v] + g.stride[axis[v]]];
    t[v] = std::clamp(fa / (fa - fb), tau, 1 - tau);
    tLo[v] = 0;
    tHi[v] = 1;
    fLo[v] = fa;
    fHi[v] = fb;
  }
  auto position = [&](int v) {
    Vec<Dim> x = g.point(from[v]);
    x[axis[v]] += t[v] * g.h[axis[v]];
    return x;
  };
  Eigen::VectorXd f;
  Points<Dim> G;
  g.vertices.resize(Dim, V);
  for (int v = 0; v < V; ++v) g.vertices.col(v) = position(v);
  field.evaluateBatch(g.vertices, f, &G);
  // Only vertices not yet converged (Newton step above 1e-9 of a cell) are iterated and
  // re-evaluated: for RBF fields each evaluation with ∇f is the expensive part.
  std::vector<int> active(static_cast<size_t>(V));
  for (int v = 0; v < V; ++v) active[static_cast<size_t>(v)] = v;
  std::vector<int> next;
  Points<Dim> X;
  Eigen::VectorXd fa;
  Points<Dim> Ga;
  for (int step = 0; step < options.newtonSteps && !active.empty(); ++step) {
    next.clear();
    for (int v : active) {
      const double slope = G(axis[v], v) * g.h[axis[v]];  // df/dt
      if (std::abs(f[v]) <= 1e-9 * std::abs(slope)) continue;  // converged
      // The end at t = 0 is the one whose sign is values[from]: keep the bracket on the sign change.
      const bool startInside = g.values[from[v]] < 0;
      // Illinois: when the same end moves twice running, the other end's value is halved, which
      // keeps false position superlinear on the near-tangent edges where Newton overshoots.
      const int moved = (f[v] < 0) == startInside ? -1 : 1;
      if (moved < 0) tLo[v] = t[v], fLo[v] = f[v];
      else tHi[v] = t[v], fHi[v] = f[v];
      if (moved == lastMoved[v]) (moved < 0 ? fHi[v] : fLo[v]) *= 0.5;
      lastMoved[v] = static_cast<signed char>(moved);
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
    field.evaluateBatch(X, fa, &Ga);
    for (size_t k = 0; k < next.size(); ++k) {
      const int v = next[k];
      g.vertices.col(v) = X.col(static_cast<Eigen::Index>(k));
      f[v] = fa[static_cast<Eigen::Index>(k)];
      G.col(v) = Ga.col(static_cast<Eigen::Index>(k));
    }
    active.swap(next);
  }
  g.gradients = G;
  if (report) report->maxAbsF = V > 0 ? f.cwiseAbs().maxCoeff() : 0.0;
}

}  // namespace hermite::detail
