#pragma once
// Internal to marching_cubes.cpp: one slab of the streamed marching cubes (MarchingOptions::cull;
// docs/maths.md, Contouring). The grid is walked in slabs of up to kSlabCells cell layers along
// z; a slab holds f only for its own (kSlabCells + 1) point layers, so memory grows with the
// grid's cross-section, not its volume. In a slab the culling octree (marching_cull.h) leaves
// the finest blocks whose sign it cannot prove; f is evaluated at their points only, and the
// contour is built from the sign-changing cells among theirs. Every value the mesh reads — the
// corners of sign-changing cells, the faces the face decider reads — is a true f, so the
// mesh is the dense grid's, vertex for vertex.

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/mesh/marching_grid.h"
#include "core/mesh/marching_memory.h"

namespace hermite::detail {

// Cell layers per slab: the octree's top block, so the blocks a slab culls are the whole grid's.
// A slab's points hold f (8 bytes), whether f is needed (1) and whether it has data (1): the
// plan of marching_memory.h.
inline constexpr int kSlabCells = kSlabPlanCells;
static_assert(kSlabPlanBytesPerPoint == sizeof(double) + 2, "the slab plan counts f, needed, valid");

// The slab of cell layers [k0, k0 + layers) of the grid over `lines` (h: the uniform grid's cell
// size): its points are the grid's point layers [k0, k0 + layers], indexed locally, placed globally.
inline MarchingGrid<3> slabGrid(const GridLines<3>& lines, const Vec<3>& h, int k0, int layers) {
  const std::array<int, 3> n = gridCells<3>(lines);
  MarchingGrid<3> g;
  g.lines = lines;
  g.h = h;
  g.n = {n[0], n[1], layers};
  g.origin = {0, 0, k0};
  g.stride = {1, std::int64_t(n[0]) + 1, (std::int64_t(n[0]) + 1) * (n[1] + 1)};
  g.pointCount = g.stride[2] * (layers + 1);
  g.values.resize(g.pointCount);
  return g;
}

// f at the points of the slab's undecided finest blocks (values elsewhere are not set), each
// point once, block by block: neighbouring points go to the field together (a partition of unity
// looks their supports up once). Batches of 2¹⁴ points, cancel polled and progress(fraction of
// the slab's points done) reported between them. Returns how many points were evaluated.
inline std::int64_t evaluateSlab(MarchingGrid<3>& g, const ImplicitField<3>& field,
                                 const std::vector<CullBlock<3>>& blocks, const CancelToken* cancel,
                                 const std::function<void(double)>& progress) {
  std::vector<char> taken(static_cast<size_t>(g.pointCount), 0);
  std::vector<std::int64_t> todo;
  for (const CullBlock<3>& b : blocks)
    forBlockPoints(g, b, [&](std::int64_t p) {
      if (taken[static_cast<size_t>(p)]) return;
      taken[static_cast<size_t>(p)] = 1;
      todo.push_back(p);
    });
  std::vector<char>().swap(taken);
  constexpr std::int64_t kChunk = 1 << 14;
  const std::int64_t total = static_cast<std::int64_t>(todo.size());
  Points<3> X;
  Eigen::VectorXd f;
  for (std::int64_t begin = 0; begin < total; begin += kChunk) {
    throwIfCancelled(cancel);
    const std::int64_t count = std::min(kChunk, total - begin);
    X.resize(3, count);
    for (std::int64_t i = 0; i < count; ++i) X.col(i) = g.point(todo[static_cast<size_t>(begin + i)]);
    field.evaluateBatch(X, f);
    for (std::int64_t i = 0; i < count; ++i) {
      if (!std::isfinite(f[i]))
        throw NumericalError("marching: f is not finite at grid point (" + std::to_string(X(0, i)) + ", " +
                             std::to_string(X(1, i)) + ", " + std::to_string(X(2, i)) + ")");
      g.values[todo[static_cast<size_t>(begin + i)]] = f[i];
    }
    if (progress) progress(double(begin + count) / double(total));
  }
  return total;
}

// The lower corners (local point indices, sorted) of the slab's cells whose corner signs differ.
// Only cells of the undecided blocks can: every other cell lies in a block proven sign-constant.
inline std::vector<std::int64_t> signChangingCells(const MarchingGrid<3>& g, const std::vector<CullBlock<3>>& blocks) {
  std::vector<std::vector<std::int64_t>> perBlock(blocks.size());
  const std::int64_t sx = g.stride[0], sy = g.stride[1], sz = g.stride[2];
#pragma omp parallel for schedule(dynamic, 16)
  for (std::int64_t bi = 0; bi < static_cast<std::int64_t>(blocks.size()); ++bi) {
    const CullBlock<3>& b = blocks[static_cast<size_t>(bi)];
    const int hi[3] = {std::min(b.lo[0] + b.size, g.n[0]), std::min(b.lo[1] + b.size, g.n[1]),
                       std::min(b.lo[2] + b.size, g.n[2])};
    for (int k = b.lo[2]; k < hi[2]; ++k)
      for (int j = b.lo[1]; j < hi[1]; ++j)
        for (int i = b.lo[0]; i < hi[0]; ++i) {
          const std::int64_t p = i + sy * j + sz * k;
          const bool in = g.inside(p);
          const std::int64_t corners[7] = {p + sx, p + sy, p + sx + sy, p + sz, p + sx + sz, p + sy + sz,
                                           p + sx + sy + sz};
          for (std::int64_t c : corners)
            if (g.inside(c) != in) {
              perBlock[static_cast<size_t>(bi)].push_back(p);
              break;
            }
        }
  }
  std::vector<std::int64_t> cells;
  for (const auto& v : perBlock) cells.insert(cells.end(), v.begin(), v.end());
  radixSort(cells);
  return cells;
}

// g.valid at the corners of the sign-changing cells (the only points whose validity the mesh
// reads: every sign-changing edge is an edge of such a cell); 0 elsewhere.
inline void slabValidity(MarchingGrid<3>& g, const ImplicitField<3>& field, const std::vector<std::int64_t>& cells,
                         const CancelToken* cancel) {
  g.valid.assign(static_cast<size_t>(g.pointCount), 0);
  std::vector<std::int64_t> todo;
  for (std::int64_t p : cells)
    for (int c = 0; c < 8; ++c) {
      const std::int64_t q = p + (c & 1) * g.stride[0] + ((c >> 1) & 1) * g.stride[1] + ((c >> 2) & 1) * g.stride[2];
      if (g.valid[static_cast<size_t>(q)]) continue;
      g.valid[static_cast<size_t>(q)] = 1;  // marks it asked; the answer follows
      todo.push_back(q);
    }
  constexpr std::size_t kChunk = 1 << 14;
  Points<3> X;
  std::vector<char> ok;
  for (std::size_t begin = 0; begin < todo.size(); begin += kChunk) {
    throwIfCancelled(cancel);
    const std::size_t count = std::min(kChunk, todo.size() - begin);
    X.resize(3, static_cast<Eigen::Index>(count));
    for (std::size_t i = 0; i < count; ++i) X.col(static_cast<Eigen::Index>(i)) = g.point(todo[begin + i]);
    field.validBatch(X, ok, g.h.norm());
    for (std::size_t i = 0; i < count; ++i) g.valid[static_cast<size_t>(todo[begin + i])] = ok[i];
  }
}

// g.edgeKeys: the sign-changing edges of the cells, both ends with data, sorted (the dense
// grid's keys, in the slab's local point indices).
inline void slabEdges(MarchingGrid<3>& g, const std::vector<std::int64_t>& cells) {
  g.edgeKeys.clear();
  for (std::int64_t p : cells)
    for (int c = 0; c < 8; ++c) {
      const std::int64_t q = p + (c & 1) * g.stride[0] + ((c >> 1) & 1) * g.stride[1] + ((c >> 2) & 1) * g.stride[2];
      for (int a = 0; a < 3; ++a) {
        if ((c >> a) & 1) continue;  // the cell's edges run from its corners with offset 0 on their axis
        const std::int64_t r = q + g.stride[a];
        if (g.inside(q) != g.inside(r) && g.isValid(q) && g.isValid(r)) g.edgeKeys.push_back(q * 3 + a);
      }
    }
  radixSort(g.edgeKeys);
  g.edgeKeys.erase(std::unique(g.edgeKeys.begin(), g.edgeKeys.end()), g.edgeKeys.end());
}

}  // namespace hermite::detail
