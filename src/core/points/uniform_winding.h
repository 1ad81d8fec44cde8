#pragma once
// The winding number of an oriented point cloud with every sample standing for the same area
// a = s² (s the spacing √(A / N) of N samples on a surface of area A):
//
//   w(x) = s² / (4π) · Σᵢ (pᵢ − x)·nᵢ / (‖pᵢ − x‖² + ¼s²)^{3/2}
//
// cloud_winding.h's sum without its per-sample areas (so without their k-nearest-neighbour pass)
// and without the far field's expansion: one pass over the samples per point, for a few points
// (the stray review's filter, stray_pockets.h). 3D.

#include <vector>

#include "core/points/hermite_samples.h"

namespace hermite {

// w at the columns `cols` of X (3 × M), spacing s > 0, in the order of cols; in parallel.
std::vector<double> uniformAreaWinding(const HermiteSamples<3>& samples, double spacing, const Points<3>& X,
                                       const std::vector<Eigen::Index>& cols);

}  // namespace hermite
