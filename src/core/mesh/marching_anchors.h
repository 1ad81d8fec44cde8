#pragma once
// Internal to marching_cubes.cpp: the anchors of MarchingOptions (points on the zero set, the
// fit's samples) that a grid misses (docs/maths.md, Contouring). An anchor is missed when its own
// cell has no sign change, the field passes through it (|f| within a quarter cell diagonal of
// zero, to first order) and has data there, and the zero set is thin there: within a cell
// diagonal along ∇f the field goes inside and back out (a solid thinner than that) or outside and
// back in (a gap). A surface that merely dips into a cell without crossing its edges is not thin
// and is not counted: the crossing is in the cell next door.

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/mesh/grid_lines.h"
#include "core/mesh/marching_grid.h"

namespace hermite::detail {

struct AnchorCells {
  std::vector<std::array<int, 3>> cell;  // the anchor's cell on the grid's lines; {-1, …} outside
  std::vector<int> byLayer;              // the anchors inside the grid, by their cell's z
  std::vector<char> seen;                // 1: its cell has a sign change
};

inline AnchorCells locateAnchors(const GridLines<3>& lines, const Points<3>& anchors) {
  AnchorCells a;
  const int m = static_cast<int>(anchors.cols());
  a.cell.resize(static_cast<size_t>(m));
  a.seen.assign(static_cast<size_t>(m), 0);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < m; ++i) {
    std::array<int, 3>& c = a.cell[static_cast<size_t>(i)];
    for (int k = 0; k < 3; ++k) c[k] = gridCellOf(lines[k], anchors(k, i));
  }
  // A counting sort by the cell's z (stable: by index within a layer).
  std::vector<int> start(lines[2].size() + 1, 0);
  const auto inside = [&](int i) {
    const std::array<int, 3>& c = a.cell[static_cast<size_t>(i)];
    return c[0] >= 0 && c[1] >= 0 && c[2] >= 0;
  };
  for (int i = 0; i < m; ++i)
    if (inside(i)) ++start[static_cast<size_t>(a.cell[static_cast<size_t>(i)][2]) + 1];
  for (size_t k = 1; k < start.size(); ++k) start[k] += start[k - 1];
  a.byLayer.resize(static_cast<size_t>(start.back()));
  for (int i = 0; i < m; ++i)
    if (inside(i)) a.byLayer[static_cast<size_t>(start[static_cast<size_t>(a.cell[static_cast<size_t>(i)][2])]++)] = i;
  return a;
}

// Marks seen the anchors in the slab's sign-changing cells (`cells`: their lower corners, local
// point indices, sorted, as signChangingCells gives them).
inline void markSeenAnchors(AnchorCells& a, const MarchingGrid<3>& g, const std::vector<std::int64_t>& cells) {
  const int k0 = g.origin[2];
  const auto zOf = [&](int i) { return a.cell[static_cast<size_t>(i)][2]; };
  const auto first = std::partition_point(a.byLayer.begin(), a.byLayer.end(), [&](int i) { return zOf(i) < k0; });
  const auto last = std::partition_point(first, a.byLayer.end(), [&](int i) { return zOf(i) < k0 + g.n[2]; });
  const std::int64_t count = last - first;
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < count; ++t) {
    const int i = *(first + t);
    const std::array<int, 3>& c = a.cell[static_cast<size_t>(i)];
    const std::int64_t p = c[0] + g.stride[1] * c[1] + g.stride[2] * (c[2] - k0);
    if (std::binary_search(cells.begin(), cells.end(), p)) a.seen[static_cast<size_t>(i)] = 1;
  }
}

// Whether the zero set at an anchor x (unit normal n = ∇f/‖∇f‖) is thin: along −n the field
// turns inside and back outside within a cell diagonal d (a solid thinner than that), or along +n
// outside and back inside (a gap). fs[first + k] = f(x − (k + 1)·d/kThinSteps·n) and
// fs[first + kThinSteps + k] = f(x + (k + 1)·d/kThinSteps·n), k < kThinSteps.
inline constexpr int kThinSteps = 8;
inline bool thinAt(const Eigen::VectorXd& fs, Eigen::Index first) {
  for (int side = 0; side < 2; ++side) {
    const bool wantInside = side == 0;  // −n: into the solid first
    bool entered = false;
    for (int k = 0; k < kThinSteps; ++k) {
      const bool inside = fs[first + side * kThinSteps + k] < 0;
      if (inside == wantInside) entered = true;
      else if (entered) return true;
    }
  }
  return false;
}

// The missed anchors (the file's comment) among those not seen: their indices.
inline std::vector<int> missedAnchors(const AnchorCells& a, const Points<3>& anchors, const ImplicitField<3>& field,
                                      double cellDiagonal) {
  std::vector<int> unseen;
  for (int i : a.byLayer)
    if (!a.seen[static_cast<size_t>(i)]) unseen.push_back(i);
  Points<3> X(3, static_cast<Eigen::Index>(unseen.size()));
  for (size_t t = 0; t < unseen.size(); ++t) X.col(static_cast<Eigen::Index>(t)) = anchors.col(unseen[t]);
  Eigen::VectorXd f, fs;
  Points<3> G;
  field.evaluateBatch(X, f, &G);
  std::vector<char> ok;
  field.validOnZeroSetBatch(X, ok);
  // Probed only where the field passes through the anchor and has data there.
  std::vector<Eigen::Index> through;
  for (Eigen::Index t = 0; t < X.cols(); ++t)
    if (ok[static_cast<size_t>(t)] && std::abs(f[t]) <= 0.25 * cellDiagonal * G.col(t).norm()) through.push_back(t);
  const Eigen::Index m = static_cast<Eigen::Index>(through.size());
  Points<3> probes(3, m * 2 * kThinSteps);
  for (Eigen::Index j = 0; j < m; ++j) {
    const Eigen::Index t = through[static_cast<size_t>(j)];
    const Vec<3> n = G.col(t).normalized();
    for (int k = 0; k < kThinSteps; ++k) {
      const double s = cellDiagonal * (k + 1) / kThinSteps;
      probes.col(j * 2 * kThinSteps + k) = X.col(t) - s * n;
      probes.col(j * 2 * kThinSteps + kThinSteps + k) = X.col(t) + s * n;
    }
  }
  field.evaluateBatch(probes, fs);
  std::vector<int> out;
  for (Eigen::Index j = 0; j < m; ++j)
    if (thinAt(fs, j * 2 * kThinSteps)) out.push_back(unseen[static_cast<size_t>(through[static_cast<size_t>(j)])]);
  return out;
}

// Their cells.
inline std::vector<std::array<int, 3>> anchorCellsOf(const AnchorCells& a, const std::vector<int>& which) {
  std::vector<std::array<int, 3>> out;
  for (int i : which) out.push_back(a.cell[static_cast<size_t>(i)]);
  return out;
}

}  // namespace hermite::detail
