#pragma once
// Which cells of a regular grid hold a sample, and which samples: the "far from the samples" tests
// of the stray-pocket review (stray_pockets.h). The cells follow the sample spacing, so a grid over
// a dense scan has far more cells than a bit per cell can afford (a million samples of a 0.2-wide
// model at cells of 0.0002: 10⁹ cells); the occupied ones, at most one per sample, are kept in a
// hash table, each with a list of its samples (24–40 B per sample in all).

#include <cstdint>
#include <vector>

#include "core/base/geometry.h"

namespace hermite {

class OccupiedCells {
 public:
  // Cells of side `cell` (> 0) with a corner at `origin`; the grid is unbounded (21 bits of index
  // per axis on either side of the origin). `samples` must outlive this (samplesWithin reads them).
  OccupiedCells(const Points<3>& samples, const Vec<3>& origin, double cell);
  // No sample lies in x's cell or the 26 around it: x is farther than `cell` from every sample
  // (and may be as near as 2√3 cells).
  bool farFromSamples(const Vec<3>& x) const;
  // The samples within r of x (indices into the samples, in no particular order), at most `limit`
  // of them (0: all). r of a few cells: it scans every cell the ball touches.
  void samplesWithin(const Vec<3>& x, double r, std::vector<int>& out, int limit = 0) const;
  double cell() const { return cell_; }

 private:
  std::uint64_t keyOf(const Vec<3>& x) const;
  std::uint64_t insert(std::uint64_t key);  // its slot
  std::int64_t slotOf(std::uint64_t key) const;  // −1: absent
  bool cellSamplesWithin(std::uint64_t key, const Vec<3>& x, double r, std::vector<int>& out, int limit) const;

  const Points<3>& samples_;
  Vec<3> origin_;
  double cell_ = 1;
  std::vector<std::uint64_t> slots_;  // open addressing; kEmpty marks a free slot
  std::vector<int> first_;            // per slot: its cell's first sample
  std::vector<int> next_;             // per sample: the next one in its cell (−1: none)
  std::uint64_t mask_ = 0;            // slots_.size() − 1 (a power of two)
};

}  // namespace hermite
