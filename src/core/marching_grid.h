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

#include "core/errors.h"
#include "core/marching.h"

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

inline double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
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
  const double cell = ext.maxCoeff() / options.resolution;
  std::int64_t s = 1;
  for (int a = 0; a < Dim; ++a) {
    g.n[a] = std::max(1, static_cast<int>(std::ceil(ext[a] / cell - 1e-9)));
    g.h[a] = ext[a] / g.n[a];
    g.stride[a] = s;
    s *= g.n[a] + 1;
  }
  g.pointCount = s;
  g.values.resize(s);
  const std::int64_t slab = g.stride[Dim - 1];
  const std::int64_t slabsPerBatch = std::max<std::int64_t>(1, (1 << 20) / slab);
  for (std::int64_t first = 0; first < s; first += slab * slabsPerBatch) {
    const std::int64_t count = std::min(s - first, slab * slabsPerBatch);
    Points<Dim> X(Dim, count);
    for (std::int64_t i = 0; i < count; ++i) X.col(i) = g.point(first + i);
    Eigen::VectorXd f;
    field.evaluateBatch(X, f);
    for (std::int64_t i = 0; i < count; ++i)
      if (!std::isfinite(f[i])) {
        std::string where;
        for (int a = 0; a < Dim; ++a) where += (a ? ", " : "") + std::to_string(X(a, i));
        throw NumericalError("marching: f is not finite at grid point (" + where + ")");
      }
    g.values.segment(first, count) = f;
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
  auto positions = [&] {
    Points<Dim> X(Dim, V);
    for (int v = 0; v < V; ++v) {
      X.col(v) = g.point(from[v]);
      X(axis[v], v) += t[v] * g.h[axis[v]];
    }
    return X;
  };
  Eigen::VectorXd f;
  Points<Dim> G;
  g.vertices = positions();
  field.evaluateBatch(g.vertices, f, &G);
  for (int step = 0; step < options.newtonSteps; ++step) {
    for (int v = 0; v < V; ++v) {
      // The end at t = 0 is the one whose sign is values[from]: keep the bracket on the sign change.
      const bool startInside = g.values[from[v]] < 0;
      // Illinois: when the same end moves twice running, the other end's value is halved, which
      // keeps false position superlinear on the near-tangent edges where Newton overshoots.
      const int moved = (f[v] < 0) == startInside ? -1 : 1;
      if (moved < 0) tLo[v] = t[v], fLo[v] = f[v];
      else tHi[v] = t[v], fHi[v] = f[v];
      if (moved == lastMoved[v]) (moved < 0 ? fHi[v] : fLo[v]) *= 0.5;
      lastMoved[v] = static_cast<signed char>(moved);
      const double slope = G(axis[v], v) * g.h[axis[v]];  // df/dt
      double tn = t[v] - f[v] / slope;
      // Outside the bracket: false position on it instead (never worse than the bracket).
      if (!std::isfinite(tn) || tn <= tLo[v] || tn >= tHi[v])
        tn = tLo[v] + (tHi[v] - tLo[v]) * fLo[v] / (fLo[v] - fHi[v]);
      t[v] = std::clamp(tn, tau, 1 - tau);
    }
    g.vertices = positions();
    field.evaluateBatch(g.vertices, f, &G);
  }
  g.gradients = G;
  if (report) report->maxAbsF = V > 0 ? f.cwiseAbs().maxCoeff() : 0.0;
}

}  // namespace hermite::detail
