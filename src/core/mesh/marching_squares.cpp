// Marching squares with the asymptotic decider; segments chained into polylines (marching.h).

#include "core/mesh/marching_squares.h"

#include <chrono>
#include <cstdint>
#include <vector>

#include "core/mesh/marching_grid.h"

namespace hermite {

namespace {

// The curve's successor and predecessor of every edge vertex (−1: none).
struct SegmentLinks {
  std::vector<int> next, prev;
};

// next[v]: the vertex the curve goes to from v. Cell corners counter-clockwise: (0,0), (1,0),
// (1,1), (0,1). A crossing is A (inside → outside along the walk) or B (outside → inside); a
// segment runs from an A to a B, which keeps the inside on the left (counter-clockwise curves).
SegmentLinks linkSegments(const detail::MarchingGrid<2>& g) {
  const int V = static_cast<int>(g.edgeKeys.size());
  SegmentLinks L{std::vector<int>(static_cast<size_t>(V), -1), std::vector<int>(static_cast<size_t>(V), -1)};
  auto link = [&](int a, int b) {
    if (!g.isVertexValid(a) && !g.isVertexValid(b)) return;  // no vertex with data: open here
    L.next[static_cast<size_t>(a)] = b;
    L.prev[static_cast<size_t>(b)] = a;
  };
  const std::int64_t sy = g.stride[1];
  for (int j = 0; j < g.n[1]; ++j)
    for (int i = 0; i < g.n[0]; ++i) {
      const std::int64_t c[4] = {i + sy * j, i + 1 + sy * j, i + 1 + sy * (j + 1), i + sy * (j + 1)};
      if (!(g.isValid(c[0]) && g.isValid(c[1]) && g.isValid(c[2]) && g.isValid(c[3]))) continue;  // no data
      // Vertex on the side from corner k to k + 1.
      const int side[4] = {g.vertexOn(c[0], 0), g.vertexOn(c[1], 1), g.vertexOn(c[3], 0), g.vertexOn(c[0], 1)};
      int ids[4], isA[4], n = 0;
      for (int k = 0; k < 4; ++k)
        if (g.inside(c[k]) != g.inside(c[(k + 1) % 4])) {
          ids[n] = side[k];
          isA[n++] = g.inside(c[k]);
        }
      if (n == 2) {
        if (isA[0]) link(ids[0], ids[1]);
        else link(ids[1], ids[0]);
      } else if (n == 4) {
        const double v0 = g.values[c[0]], v1 = g.values[c[1]], v2 = g.values[c[2]], v3 = g.values[c[3]];
        const bool outsideConnected = (v0 * v2 - v1 * v3) / (v0 + v2 - v1 - v3) >= 0;
        for (int k = 0; k < 4; ++k) {
          const int m = (k + 1) % 4;
          if (outsideConnected && !isA[k]) link(ids[m], ids[k]);  // inside corner cut off: A → B
          if (!outsideConnected && isA[k]) link(ids[k], ids[m]);  // outside corner cut off: A → B
        }
      }
    }
  return L;
}

// The linked vertices as polylines: open curves first, from their start on the box boundary,
// then the closed ones.
std::vector<Polyline2d> chainPolylines(const detail::MarchingGrid<2>& g, const SegmentLinks& L) {
  const int V = static_cast<int>(L.next.size());
  std::vector<Polyline2d> lines;
  std::vector<char> used(static_cast<size_t>(V), 0);
  auto trace = [&](int start) {
    std::vector<int> chain;
    int v = start;
    while (v >= 0 && !used[static_cast<size_t>(v)]) {
      used[static_cast<size_t>(v)] = 1;
      chain.push_back(v);
      v = L.next[static_cast<size_t>(v)];
    }
    if (chain.size() < 2) return;  // a vertex whose cells all touch a no-data point
    Polyline2d line;
    line.closed = v == start;
    line.points.resize(2, static_cast<Eigen::Index>(chain.size()));
    for (size_t k = 0; k < chain.size(); ++k) line.points.col(static_cast<Eigen::Index>(k)) = g.vertices.col(chain[k]);
    lines.push_back(std::move(line));
  };
  for (int v = 0; v < V; ++v)
    if (L.prev[static_cast<size_t>(v)] < 0 && !used[static_cast<size_t>(v)]) trace(v);
  for (int v = 0; v < V; ++v)
    if (!used[static_cast<size_t>(v)]) trace(v);
  return lines;
}

}  // namespace

std::vector<Polyline2d> marchingSquares(const ImplicitField<2>& field, const Box<2>& box,
                                        const MarchingOptions& options, MarchingReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  detail::MarchingGrid<2> g = detail::sampleGrid<2>(field, detail::marchingLines<2>(box, options.resolution),
                                                          detail::marchingCellSize<2>(box, options.resolution),
                                                          options, report);
  detail::placeEdgeVertices<2>(g, field, options, report);
  std::vector<Polyline2d> lines = chainPolylines(g, linkSegments(g));
  if (report) report->totalMs = msSince(t0);
  return lines;
}

}  // namespace hermite
