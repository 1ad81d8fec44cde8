#include "core/mesh/marching_memory.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

namespace hermite {

template <int Dim>
std::array<int, Dim> marchingCells(const Box<Dim>& box, int resolution) {
  const Vec<Dim> ext = box.extent();
  const double cell = ext.maxCoeff() / resolution;
  std::array<int, Dim> n{};
  for (int a = 0; a < Dim; ++a) n[a] = std::max(1, static_cast<int>(std::ceil(ext[a] / cell - 1e-9)));
  return n;
}

template <int Dim>
PlannedAllocation marchingGridPlan(const std::array<int, Dim>& n, int resolution) {
  std::uint64_t points = 1;
  std::string grid;
  for (int a = 0; a < Dim; ++a) {
    points = saturatingProduct({points, std::uint64_t(n[a]) + 1});
    grid += (a ? " x " : "") + std::to_string(n[a] + 1);
  }
  return {saturatingProduct({points, kMarchingBytesPerPoint}),
          std::string(Dim == 3 ? "marching cubes" : "marching squares") + " at resolution " +
              std::to_string(resolution) + " (a grid of " + grid + " points, " +
              std::to_string(kMarchingBytesPerPoint) + " bytes each)"};
}

template <int Dim>
PlannedAllocation marchingGridPlan(const Box<Dim>& box, int resolution) {
  return marchingGridPlan<Dim>(marchingCells<Dim>(box, resolution), resolution);
}

PlannedAllocation marchingSlabPlan(const std::array<int, 3>& n, int resolution) {
  const int layers = std::min(n[2], kSlabPlanCells) + 1;
  const std::uint64_t points =
      saturatingProduct({std::uint64_t(n[0]) + 1, std::uint64_t(n[1]) + 1, std::uint64_t(layers)});
  return {saturatingProduct({points, kSlabPlanBytesPerPoint}),
          "marching cubes at resolution " + std::to_string(resolution) + " (slabs of " + std::to_string(n[0] + 1) +
              " x " + std::to_string(n[1] + 1) + " x " + std::to_string(layers) + " points, " +
              std::to_string(kSlabPlanBytesPerPoint) + " bytes each)"};
}

PlannedAllocation marchingSlabPlan(const Box<3>& box, int resolution) {
  return marchingSlabPlan(marchingCells<3>(box, resolution), resolution);
}

template std::array<int, 2> marchingCells<2>(const Box<2>&, int);
template std::array<int, 3> marchingCells<3>(const Box<3>&, int);
template PlannedAllocation marchingGridPlan<2>(const Box<2>&, int);
template PlannedAllocation marchingGridPlan<2>(const std::array<int, 2>&, int);
template PlannedAllocation marchingGridPlan<3>(const std::array<int, 3>&, int);
template PlannedAllocation marchingGridPlan<3>(const Box<3>&, int);

}  // namespace hermite
