#pragma once
// Normals for raw clouds (docs/maths.md, Normal estimation): PCA over the k nearest
// neighbours (the normal is the eigenvector of the smallest eigenvalue of the neighbourhood's
// covariance), then consistent orientation by propagation over a minimum spanning tree of the
// k-nearest-neighbour graph with edge cost 1 − |nᵢ·nⱼ| (Hoppe et al. 1992), and per connected
// component a final flip so the sample farthest from the component's centroid points away
// from it (outward for closed shapes).

#include "core/base/geometry.h"

namespace hermite {

struct NormalEstimationOptions {
  int neighbours = 10;  // k ≥ Dim (PCA needs a spread); 10 fits typical scanned clouds
};

// Unit normals (Dim × N) for the columns of `points` (Dim × N, N ≥ 2). InputError when N < 2.
template <int Dim>
Points<Dim> estimateNormals(const Points<Dim>& points, const NormalEstimationOptions& options = {});

// Flips every normal (the GUI's "flip" button): n ↦ −n.
template <int Dim>
void flipNormals(Points<Dim>& normals) {
  normals = -normals;
}

}  // namespace hermite
