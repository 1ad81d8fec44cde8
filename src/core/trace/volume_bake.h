#pragma once
// Baking f of a 3D field into a grid for the GPU tracer (docs/maths.md, Volume bake and sphere tracing), with per-brick
// Lipschitz bounds that make sphere-tracing steps safe and cull bricks without a zero crossing.
//
// Units: values are f in the field's own units; Lipschitz bounds in f-units per world unit.
// Layout: value of sample (i, j, k) at index i + R·(j + R·k) (x fastest), the layout of an
// R×R×R GL_R32F 3D texture uploaded with width = x. Bricks likewise: bx + Bx·(by + By·bz).

#include <cstdint>
#include <vector>

#include "core/base/cancel_token.h"
#include "core/base/implicit_field.h"

namespace hermite {

// Lipschitz bounds of f on a regular grid of boxes ("bricks") over `bounds`. Brick b along an
// axis covers [lo + b·size, min(lo + (b+1)·size, hi)].
struct BrickGrid {
  Box<3> bounds;
  Eigen::Array3i count = Eigen::Array3i::Zero();  // bricks per axis
  Vec<3> size = Vec<3>::Zero();                   // brick edge, world units
  std::vector<double> lipschitz;                  // ≥ sup ‖∇f‖ over the brick (field.lipschitzBound)
  std::vector<double> centerValue;                // f at the brick box's centre
  // 0 only where |f(centre)| > L·(half-diagonal): a proof that f has no zero in the brick.
  std::vector<std::uint8_t> mayContainZero;

  int index(int bx, int by, int bz) const { return bx + count.x() * (by + count.y() * bz); }
  int brickCount() const { return count.prod(); }
  Box<3> brickBox(int bx, int by, int bz) const;
  // The brick containing x (clamped to the grid).
  Eigen::Array3i locate(const Vec<3>& x) const;
};

// Bounds over `count` bricks per axis of equal size; threaded over bricks.
BrickGrid computeBrickGrid(const ImplicitField<3>& field, const Box<3>& bounds, const Eigen::Array3i& count);

struct VolumeBakeOptions {
  int resolution = 128;  // R samples per axis, ≥ 2 (vertex-centred: R − 1 cells)
  int brickCells = 8;    // cells per brick edge, ≥ 1; 8 at R = 128 gives 16³ bricks
  // Polled slab by slab (a few z-planes, ~64k samples); bakeVolume throws Cancelled when set.
  const CancelToken* cancel = nullptr;
};

struct VolumeBake {
  Box<3> bounds;
  int resolution = 0;         // R
  std::vector<float> values;  // R³, x fastest; sample (i,j,k) at lo + (i,j,k)·(hi − lo)/(R − 1)
  // R³ like values: 1 where a zero of f at the sample would be no surface (the field has no data
  // on its zero set there: ImplicitField::validOnZeroSet), else 0; empty for a field with data
  // everywhere.
  std::vector<std::uint8_t> noData;
  int brickCells = 0;
  // Brick (bx,by,bz) covers samples bx·C … min((bx+1)·C, R−1) per axis (C = brickCells): the
  // cells whose trilinear interpolant depends only on these samples.
  BrickGrid bricks;
  std::vector<float> brickMin, brickMax;  // min / max of the baked samples of each brick
  double sampleMs = 0;  // evaluating f on the grid, wall clock
  double brickMs = 0;   // Lipschitz bounds, centre values and min/max of every brick

  Vec<3> spacing() const { return bounds.extent() / double(resolution - 1); }
  Vec<3> samplePosition(int i, int j, int k) const {
    return bounds.lo + spacing().cwiseProduct(Vec<3>(i, j, k));
  }
  float value(int i, int j, int k) const { return values[i + resolution * (j + std::size_t(resolution) * k)]; }
  // The trilinear interpolant of the samples at x (clamped to the bounds): what the GPU tracer's
  // linearly filtered 3D texture returns, in double.
  double interpolate(const Vec<3>& x) const;
  // The trilinear interpolant of the samples has no zero in a brick whose min > 0 or max < 0
  // (it is a convex combination of them there); its gradient norm is ≤ √3·L of the field.
  bool interpolantMayContainZero(int brick) const { return brickMin[brick] <= 0.0f && brickMax[brick] >= 0.0f; }
};

// Threaded (OpenMP, all workers) bake of f over `bounds`. Throws InputError for a resolution
// < 2, brickCells < 1 or an empty box.
VolumeBake bakeVolume(const ImplicitField<3>& field, const Box<3>& bounds, const VolumeBakeOptions& options = {});

}  // namespace hermite
