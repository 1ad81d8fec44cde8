#pragma once
// The grid lines of marching squares / cubes per axis: world coordinates, strictly increasing.
// A uniform grid has n + 1 equally spaced lines per axis; a refined one has more lines in some
// intervals (grid_refinement.h). The grid stays a tensor product (rectilinear), so every cell
// shares whole faces with its neighbours and the contour stays watertight.

#include <algorithm>
#include <array>
#include <vector>

#include "core/base/geometry.h"

namespace hermite {

template <int Dim>
using GridLines = std::array<std::vector<double>, Dim>;

// The uniform lines of `cells[a]` equal cells per axis over `box`: lo + (hi − lo)·i / cells.
template <int Dim>
GridLines<Dim> uniformGridLines(const Box<Dim>& box, const std::array<int, Dim>& cells) {
  GridLines<Dim> lines;
  for (int a = 0; a < Dim; ++a) {
    const double step = box.extent()[a] / cells[a];
    lines[a].resize(static_cast<size_t>(cells[a]) + 1);
    for (int i = 0; i <= cells[a]; ++i) lines[a][static_cast<size_t>(i)] = box.lo[a] + step * i;
  }
  return lines;
}

// Cells per axis: one fewer than the lines.
template <int Dim>
std::array<int, Dim> gridCells(const GridLines<Dim>& lines) {
  std::array<int, Dim> n{};
  for (int a = 0; a < Dim; ++a) n[a] = static_cast<int>(lines[a].size()) - 1;
  return n;
}

// The cell interval of coordinate x on one axis's lines: i with lines[i] ≤ x < lines[i + 1]
// (the last cell for x on the last line); −1 outside [lines.front(), lines.back()].
// Starts where uniform lines would put x and searches only when that misses by more than a line.
inline int gridCellOf(const std::vector<double>& lines, double x) {
  if (!(x >= lines.front() && x <= lines.back())) return -1;
  const int last = static_cast<int>(lines.size()) - 2;  // the last cell
  const double t = (x - lines.front()) / (lines.back() - lines.front());
  int i = std::clamp(static_cast<int>(t * (last + 1)), 0, last);
  if (lines[static_cast<size_t>(i)] > x) --i;
  else if (i < last && lines[static_cast<size_t>(i) + 1] <= x) ++i;
  if (i >= 0 && lines[static_cast<size_t>(i)] <= x && (i == last || x < lines[static_cast<size_t>(i) + 1])) return i;
  const auto it = std::upper_bound(lines.begin(), lines.end(), x);
  return std::min(static_cast<int>(it - lines.begin()) - 1, last);
}

// The lines with each interval i of axis a where split[a][i] is set cut into `factor` equal
// parts (split[a] has one entry per interval).
template <int Dim>
GridLines<Dim> splitGridIntervals(const GridLines<Dim>& lines, const std::array<std::vector<char>, Dim>& split,
                                  int factor) {
  GridLines<Dim> out;
  for (int a = 0; a < Dim; ++a) {
    const std::vector<double>& l = lines[a];
    out[a].push_back(l.front());
    for (size_t i = 0; i + 1 < l.size(); ++i) {
      if (split[a][i])
        for (int k = 1; k < factor; ++k) out[a].push_back(l[i] + (l[i + 1] - l[i]) * k / factor);
      out[a].push_back(l[i + 1]);
    }
  }
  return out;
}

// Per axis, the intervals within `reach` cells of one of `cells` (cell indices on `lines`).
template <int Dim>
std::array<std::vector<char>, Dim> intervalsNear(const GridLines<Dim>& lines,
                                                 const std::vector<std::array<int, Dim>>& cells, int reach) {
  std::array<std::vector<char>, Dim> near;
  for (int a = 0; a < Dim; ++a) near[a].assign(lines[a].size() - 1, 0);
  for (const std::array<int, Dim>& c : cells)
    for (int a = 0; a < Dim; ++a) {
      const int n = static_cast<int>(near[a].size());
      for (int i = std::max(c[a] - reach, 0); i <= std::min(c[a] + reach, n - 1); ++i) near[a][static_cast<size_t>(i)] = 1;
    }
  return near;
}

// A grid edge: its axis and the line indices of its lower end (axis −1: none).
struct GridEdge {
  int axis = -1;
  std::array<int, 3> at{};
};

// The grid edge a contour vertex lies on: two of its coordinates are grid lines exactly (marching
// cubes places a vertex along its edge at t ∈ [τ, 1 − τ], so the third lies strictly between two
// lines). Axis −1 for a point on no edge (a cube's centre vertex, a point off the grid).
inline GridEdge gridEdgeOf(const GridLines<3>& lines, const Vec<3>& p) {
  GridEdge e;
  for (int a = 0; a < 3; ++a) {
    const std::vector<double>& l = lines[a];
    const auto it = std::lower_bound(l.begin(), l.end(), p[a]);
    e.at[a] = static_cast<int>(it - l.begin());
    if (it != l.end() && *it == p[a]) continue;
    if (e.axis >= 0 || it == l.begin() || it == l.end()) return GridEdge{};
    e.axis = a;
    --e.at[a];
  }
  return e;
}

}  // namespace hermite
