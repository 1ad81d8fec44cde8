#pragma once
// A C¹ spline of bicubic Hermite patches over knots u₀ < … < uₙ (s direction) and
// v₀ < … < vₘ (t direction), built from data at the knots: points X, partials Xu, Xv and twists
// Xuv. Patch (i, j) on [uᵢ, uᵢ₊₁] × [vⱼ, vⱼ₊₁] has local s = (u − uᵢ)/Δuᵢ, t = (v − vⱼ)/Δvⱼ, so
// its s-tangents are Δuᵢ·Xu, t-tangents Δvⱼ·Xv and twists ΔuᵢΔvⱼ·Xuv (docs/maths.md, Patches). Shared
// knot data make neighbouring patches join with C¹ continuity.

#include <functional>
#include <vector>

#include "core/patch/hermite_patch.h"

namespace hermite {

// Data of a surface at one knot (u, v): the point and its exact partial derivatives.
struct KnotData {
  Vec<3> X, Xu, Xv, Xuv;
};

class PatchGrid {
 public:
  // Samples `surface` at every knot pair. Knots strictly increasing, ≥ 2 each; else InputError.
  PatchGrid(std::vector<double> uKnots, std::vector<double> vKnots,
            const std::function<KnotData(double u, double v)>& surface);

  // From data at every knot pair: data[a · vKnots.size() + b] at (u_a, v_b) (row-major in u).
  PatchGrid(std::vector<double> uKnots, std::vector<double> vKnots, const std::vector<KnotData>& data);
  static std::vector<KnotData> sampleKnots(const std::vector<double>& u, const std::vector<double>& v,
                                           const std::function<KnotData(double u, double v)>& surface);

  int patchesU() const { return static_cast<int>(u_.size()) - 1; }
  int patchesV() const { return static_cast<int>(v_.size()) - 1; }
  const HermitePatch& patch(int i, int j) const { return patches_[i * patchesV() + j]; }
  const std::vector<double>& uKnots() const { return u_; }
  const std::vector<double>& vKnots() const { return v_; }

  // X and derivatives with respect to the global (u, v) (clamped to the knot range).
  SurfacePoint evaluate(double u, double v) const;

  // Triangles over the grid with `samples` × `samples` points per patch (shared edges
  // duplicated per patch): positions and unit normals (3 × V), triangles (3 × T, CCW seen from
  // the normal side Xu × Xv).
  struct Tessellation {
    Points<3> positions, normals;
    Eigen::Matrix<int, 3, Eigen::Dynamic> triangles;
  };
  Tessellation tessellate(int samples) const;

 private:
  std::vector<double> u_, v_;
  std::vector<HermitePatch> patches_;  // patchesU × patchesV, row-major in u
};

// The study torus X(u, v) = ((2 + cos v) cos u, (2 + cos v) sin u, sin v) with exact partials.
KnotData torusKnotData(double u, double v);

}  // namespace hermite
