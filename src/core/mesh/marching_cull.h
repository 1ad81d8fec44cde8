#pragma once
// Internal to marching_grid.h: the octree that skips f where the zero set cannot be
// (MarchingOptions::cull; docs/maths.md, Contouring).
//
// Blocks of 4·2^k cells per axis are tested from the coarsest level down: a block whose centre
// value exceeds L·r (L = the field's Lipschitz bound over the block, r its half-diagonal) cannot
// change sign, so its grid points only need that sign (a stand-in of that sign); otherwise it
// splits into its 2^Dim children, and a finest block (4 cells) that is not proven needs f at all
// its points. Exact: every cell with a sign change, and every face the face decider reads,
// lies in a finest block that is evaluated, so the mesh is the dense one.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/implicit_field.h"

namespace hermite::detail {

template <int Dim>
struct MarchingGrid;

// One block of the octree: its lower corner in grid cells, its size in cells, and the Lipschitz
// bound it uses (its own above kOwnBoundCells or where the ancestor's is ∞, else the nearest
// such ancestor's).
template <int Dim>
struct CullBlock {
  std::array<int, Dim> lo{};
  int size = 0;
  double lipschitz = std::numeric_limits<double>::infinity();  // none yet: the block computes its own
};

inline constexpr int kFinestCells = 4;     // cells per axis of a finest block
inline constexpr int kOwnBoundCells = 16;  // blocks this size and larger get their own bound

// The block's box in world coordinates (clipped to the grid).
template <int Dim>
Box<Dim> cullBlockBox(const MarchingGrid<Dim>& g, const CullBlock<Dim>& b) {
  Box<Dim> box;
  for (int a = 0; a < Dim; ++a) {
    box.lo[a] = g.lines[a][static_cast<size_t>(b.lo[a] + g.origin[a])];
    box.hi[a] = g.lines[a][static_cast<size_t>(std::min(b.lo[a] + b.size, g.n[a]) + g.origin[a])];
  }
  return box;
}

// Calls visit(p) for every grid point of the block (clipped to the grid).
template <int Dim, class F>
void forBlockPoints(const MarchingGrid<Dim>& g, const CullBlock<Dim>& b, F&& visit) {
  std::array<int, Dim> hi{};
  for (int a = 0; a < Dim; ++a) hi[a] = std::min(b.lo[a] + b.size, g.n[a]);
  if constexpr (Dim == 2) {
    for (int j = b.lo[1]; j <= hi[1]; ++j)
      for (int i = b.lo[0]; i <= hi[0]; ++i) visit(i + g.stride[1] * j);
  } else {
    for (int k = b.lo[2]; k <= hi[2]; ++k)
      for (int j = b.lo[1]; j <= hi[1]; ++j)
        for (int i = b.lo[0]; i <= hi[0]; ++i) visit(i + g.stride[1] * j + g.stride[2] * k);
  }
}

// Walks the octree coarse to fine: proven(b, standIn) for each block proven sign-constant (standIn:
// a lower bound of |f| there with f's sign), undecided(b) for each finest block that is not.
// Blocks tested: centre f in one batch per level.
template <int Dim, class Proven, class Undecided>
void walkCullOctree(const MarchingGrid<Dim>& g, const ImplicitField<Dim>& field, const CancelToken* cancel,
                    Proven&& proven, Undecided&& undecided) {
  int top = kFinestCells;
  const int longest = *std::max_element(g.n.begin(), g.n.end());
  while (top < longest && top < 64) top *= 2;
  std::vector<CullBlock<Dim>> level;
  {
    std::array<int, Dim> count{};
    std::int64_t total = 1;
    for (int a = 0; a < Dim; ++a) {
      count[a] = (g.n[a] + top - 1) / top;
      total *= count[a];
    }
    for (std::int64_t i = 0; i < total; ++i) {
      CullBlock<Dim> b;
      std::int64_t rest = i;
      for (int a = 0; a < Dim; ++a) {
        b.lo[a] = static_cast<int>(rest % count[a]) * top;
        rest /= count[a];
      }
      b.size = top;
      level.push_back(b);
    }
  }
  std::vector<CullBlock<Dim>> next;
  Points<Dim> centres, gc;
  Eigen::VectorXd fc, radius;
  while (!level.empty()) {
    throwIfCancelled(cancel);
    const std::int64_t m = static_cast<std::int64_t>(level.size());
    centres.resize(Dim, m);
    radius.resize(m);
    for (std::int64_t i = 0; i < m; ++i) {
      const Box<Dim> box = cullBlockBox(g, level[static_cast<size_t>(i)]);
      centres.col(i) = box.center();
      radius[i] = 0.5 * box.extent().norm();
    }
    field.evaluateBatch(centres, fc, &gc);
#pragma omp parallel for schedule(dynamic, 4)
    for (std::int64_t i = 0; i < m; ++i) {
      CullBlock<Dim>& b = level[static_cast<size_t>(i)];
      // Its own bound when large, or when the ancestor's proves nothing (∞ where the ancestor
      // reaches the edge of a field's data, while the block may lie wholly on one side) — unless
      // no bound can prove it: L ≥ ‖∇f(c)‖, so |f(c)| ≤ ‖∇f(c)‖·r fails the test whatever L is
      // (the blocks the surface crosses; their bound, over many supports, was half the culling
      // time). Their children then compute their own bounds, which are tighter.
      if (b.size < kOwnBoundCells && std::isfinite(b.lipschitz)) continue;
      const bool hopeless = std::isfinite(fc[i]) && std::abs(fc[i]) <= gc.col(i).norm() * radius[i];
      b.lipschitz = hopeless ? std::numeric_limits<double>::infinity() : field.lipschitzBound(cullBlockBox(g, b));
    }
    next.clear();
    for (std::int64_t i = 0; i < m; ++i) {
      const CullBlock<Dim>& b = level[static_cast<size_t>(i)];
      const double margin = b.lipschitz * radius[i] * (1 + 1e-9);
      if (std::isfinite(fc[i]) && std::isfinite(margin) && std::abs(fc[i]) > margin) {
        // The stand-in |f(c)| − L·r is a lower bound of |f| in the block, with its sign.
        const double bound = std::max(std::abs(fc[i]) - margin, 1e-300);
        const double standIn = fc[i] < 0 ? -bound : bound;
        proven(b, standIn);
      } else if (b.size == kFinestCells) {
        undecided(b);
      } else {
        const int half = b.size / 2;
        for (int ch = 0; ch < (1 << Dim); ++ch) {
          CullBlock<Dim> c = b;
          c.size = half;
          bool inside = true;
          for (int a = 0; a < Dim; ++a) {
            c.lo[a] += ((ch >> a) & 1) * half;
            inside = inside && c.lo[a] < g.n[a];
          }
          if (inside) next.push_back(c);
        }
      }
    }
    level.swap(next);
  }
}

// Fills g.values with same-signed stand-ins at the points of blocks proven sign-constant and
// returns which points still need f (needed[p] = 1).
template <int Dim>
std::vector<char> cullBlocks(MarchingGrid<Dim>& g, const ImplicitField<Dim>& field, const CancelToken* cancel) {
  std::vector<char> needed(static_cast<size_t>(g.pointCount), 0);
  const auto proven = [&](const CullBlock<Dim>& b, double standIn) {
    forBlockPoints(g, b, [&](std::int64_t p) { g.values[p] = standIn; });
  };
  const auto undecided = [&](const CullBlock<Dim>& b) {
    forBlockPoints(g, b, [&](std::int64_t p) { needed[static_cast<size_t>(p)] = 1; });
  };
  walkCullOctree(g, field, cancel, proven, undecided);
  return needed;
}

// The finest blocks the octree cannot prove sign-constant (the only ones whose cells can change
// sign), in the order of the walk.
template <int Dim>
std::vector<CullBlock<Dim>> undecidedBlocks(const MarchingGrid<Dim>& g, const ImplicitField<Dim>& field,
                                            const CancelToken* cancel) {
  std::vector<CullBlock<Dim>> out;
  walkCullOctree(
      g, field, cancel, [](const CullBlock<Dim>&, double) {}, [&](const CullBlock<Dim>& b) { out.push_back(b); });
  return out;
}

}  // namespace hermite::detail
