#pragma once
// The grid of marching squares / cubes sized before it is allocated (core/base/memory_check.h).
// Each grid point holds f (8 bytes) and a flag saying whether f is evaluated (1 byte): 9 bytes
// per point, (cells + 1) points per axis. The contour's vertices grow with the surface, not the
// volume, and are not counted: the plan is a lower bound of the peak.

#include <array>

#include "core/base/geometry.h"
#include "core/base/memory_check.h"

namespace hermite {

inline constexpr int kMarchingBytesPerPoint = 9;
inline constexpr const char* kMarchingRemedy = "use a lower resolution (mesh --resolution)";

// Cells per axis over `box` at `resolution` cells along its longest side (the others in
// proportion, at least 1): the layout marchingCubes / marchingSquares sample.
template <int Dim>
std::array<int, Dim> marchingCells(const Box<Dim>& box, int resolution);

// The grid's plan: "marching cubes at resolution 4096 (a 4097 x 4097 x 4097 grid)".
template <int Dim>
PlannedAllocation marchingGridPlan(const Box<Dim>& box, int resolution);
// The same for a grid of n cells per axis (a refined grid, grid_lines.h); `resolution` names it.
template <int Dim>
PlannedAllocation marchingGridPlan(const std::array<int, Dim>& n, int resolution);

// Streamed marching cubes (MarchingOptions::cull, the default) holds one slab of the grid at a
// time: min(64, cells along z) + 1 point layers of the grid's cross-section, 10 bytes per point
// (f, whether it is evaluated, whether it has data). "marching cubes at resolution 4096 (slabs of
// 4097 x 4097 x 65 points, 10 bytes each)".
inline constexpr int kSlabPlanCells = 64;
inline constexpr int kSlabPlanBytesPerPoint = 10;
PlannedAllocation marchingSlabPlan(const Box<3>& box, int resolution);
PlannedAllocation marchingSlabPlan(const std::array<int, 3>& n, int resolution);

}  // namespace hermite
