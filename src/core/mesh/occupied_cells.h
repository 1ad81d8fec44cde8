#pragma once
// Which cells of a regular grid hold a sample: the "far from the samples" test of the stray-pocket
// review (stray_pockets.h). The cells follow the sample spacing, so a grid over a dense scan has
// far more cells than a bit per cell can afford (a million samples of a 0.2-wide model at cells
// of 0.0002: 10⁹ cells); the occupied ones, at most one per sample, are kept in a hash set.

#include <cstdint>
#include <vector>

#include "core/base/geometry.h"

namespace hermite {

class OccupiedCells {
 public:
  // Cells of side `cell` (> 0) with a corner at `origin`; the grid is unbounded (21 bits of index
  // per axis on either side of the origin).
  OccupiedCells(const Points<3>& samples, const Vec<3>& origin, double cell);
  // No sample lies in x's cell or the 26 around it: x is farther than `cell` from every sample
  // (and may be as near as 2√3 cells).
  bool farFromSamples(const Vec<3>& x) const;
  double cell() const { return cell_; }

 private:
  std::uint64_t keyOf(const Vec<3>& x) const;
  void insert(std::uint64_t key);
  bool contains(std::uint64_t key) const;

  Vec<3> origin_;
  double cell_ = 1;
  std::vector<std::uint64_t> slots_;  // open addressing; kEmpty marks a free slot
  std::uint64_t mask_ = 0;            // slots_.size() − 1 (a power of two)
};

}  // namespace hermite
