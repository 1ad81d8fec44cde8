#pragma once
// Points in lexicographic order of their coordinates: what finds exact repeats of a position
// (the samples' duplicates, a mesh's vertices at one position).

#include <vector>

#include "core/base/geometry.h"

namespace hermite {

// The column indices of P (Dim × N) sorted by coordinates, equal points by index (so the first of
// a run of equal points is its smallest index); O(N log N), threaded.
template <int Dim>
std::vector<Eigen::Index> lexicographicOrder(const Points<Dim>& P);

}  // namespace hermite
