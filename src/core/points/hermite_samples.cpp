#include "core/points/hermite_samples.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "core/base/errors.h"
#include "core/base/format_number.h"
#include "core/base/radix_sort.h"
#include "core/points/flat_cell_map.h"
#include "core/points/lexicographic_order.h"

namespace hermite {

namespace {

// At most 2^20 cells per axis keeps every cell index of the spacing grid in 21 bits.
constexpr int kCellBits = 21;
constexpr double kMaxCellsPerAxis = double(1 << 20);

template <int Dim>
std::string formatVector(const Vec<Dim>& v) {
  std::string s = "(";
  for (int k = 0; k < Dim; ++k) s += (k ? ", " : "") + formatNumber(v[k]);
  return s + ")";
}

// The spacing search's uniform grid: cell indices from the corner lo in cells of side h, packed
// into a 64-bit key, kCellBits bits per axis.
using CellKey = std::uint64_t;
template <int Dim>
using Cell = std::array<std::int64_t, Dim>;

template <int Dim>
Cell<Dim> cellOf(const Vec<Dim>& p, const Vec<Dim>& lo, double h) {
  Cell<Dim> c;
  for (int k = 0; k < Dim; ++k)
    c[k] = static_cast<std::int64_t>(std::min(std::floor((p[k] - lo[k]) / h), kMaxCellsPerAxis));
  return c;
}

template <int Dim>
CellKey keyOf(const Cell<Dim>& c) {
  CellKey key = 0;
  for (int k = 0; k < Dim; ++k) key = (key << kCellBits) | static_cast<CellKey>(c[k]);
  return key;
}

// The grid's cell size: first the one that gives one point per cell if the points filled their
// bounding box; samples on a curve or surface fill a thin part of it, so it shrinks until at
// least n/4 cells are occupied, jumping by the growth rate (the data's apparent dimension) once
// known, but not below minCell.
template <int Dim>
double spacingCellSize(const Points<Dim>& points, const Vec<Dim>& lo, const Vec<Dim>& extent, double minCell) {
  const Eigen::Index n = points.cols();
  double volume = 1.0;
  int spannedAxes = 0;
  for (int k = 0; k < Dim; ++k)
    if (extent[k] > 0) volume *= extent[k], ++spannedAxes;
  double cell = std::max(minCell, std::pow(volume / double(n), 1.0 / spannedAxes));
  std::vector<CellKey> keys(static_cast<std::size_t>(n));
  double previousCell = 0;
  double previousOccupied = 0;
  for (int attempt = 0;; ++attempt) {
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) keys[i] = keyOf<Dim>(cellOf<Dim>(points.col(i), lo, cell));
    radixSort(keys);
    const double occupied = double(std::unique(keys.begin(), keys.end()) - keys.begin());
    if (4 * occupied >= double(n) || cell <= minCell || attempt >= 40) break;
    double factor = 0.5;
    if (previousOccupied > 0 && occupied > previousOccupied) {
      const double dimension =
          std::clamp(std::log(occupied / previousOccupied) / std::log(previousCell / cell), 1.0, double(Dim));
      factor = std::clamp(std::pow(occupied / (0.5 * double(n)), 1.0 / dimension), 1.0 / 1024, 0.5);
    }
    previousCell = cell;
    previousOccupied = occupied;
    cell = std::max(minCell, factor * cell);
  }
  return cell;
}

// The points bucketed in the grid for nearest-neighbour queries: sorted by cell, copied so
// that a cell's points are contiguous in memory.
template <int Dim>
class CellIndex {
 public:
  CellIndex(const Points<Dim>& points, const Vec<Dim>& lo, const Vec<Dim>& extent, double cell)
      : lo_(lo), cell_(cell), sorted_(Dim, points.cols()), maxCell_(cellOf<Dim>(lo + extent, lo, cell)) {
    const Eigen::Index n = points.cols();
    std::vector<std::pair<CellKey, Eigen::Index>> byCell(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) byCell[i] = {keyOf<Dim>(cellOf<Dim>(points.col(i), lo, cell)), i};
    radixSort(byCell);  // (key, index): a strict total order
#pragma omp parallel for schedule(static)
    for (Eigen::Index s = 0; s < n; ++s) sorted_.col(s) = points.col(byCell[s].second);
    Eigen::Index occupied = 0;
    for (Eigen::Index s = 0; s < n; ++s) occupied += s == 0 || byCell[s].first != byCell[s - 1].first;
    cells_ = FlatCellMap(static_cast<std::size_t>(occupied));
    for (Eigen::Index s = 0; s < n;) {
      Eigen::Index e = s + 1;
      while (e < n && byCell[e].first == byCell[s].first) ++e;
      cells_.insert(byCell[s].first, s, e);
      s = e;
    }
  }

  Eigen::Index size() const { return sorted_.cols(); }

  // The distance from sorted point `self` to its nearest other point: rings of cells of growing
  // Chebyshev radius about its cell until no unvisited point can be nearer, or every point when
  // the rings would cover more cells than there are points (an isolated point).
  double nearestDistance(Eigen::Index self) const {
    const Eigen::Index n = size();
    const Cell<Dim> c = cellOf<Dim>(sorted_.col(self), lo_, cell_);
    double best2 = std::numeric_limits<double>::infinity();
    std::int64_t lastRing = 0;  // beyond it no cell holds points
    for (int k = 0; k < Dim; ++k) lastRing = std::max({lastRing, c[k], maxCell_[k] - c[k]});
    double cubeCells = 0;
    for (std::int64_t ring = 0; ring <= lastRing; ++ring) {
      // Rings 0 … ring−1 are done: every point not yet visited lies at least (ring−1)·h away
      // along some axis (less a margin for rounding of points on cell boundaries).
      if (ring > 1 && std::sqrt(best2) <= (double(ring - 1) - 1e-6) * cell_) break;
      cubeCells += std::pow(2.0 * double(ring) + 1.0, Dim);
      if (cubeCells > 4.0 * double(n))
        return std::sqrt(nearestIn(self, 0, n, std::numeric_limits<double>::infinity()));
      best2 = nearestInRing(self, c, ring, best2);
    }
    return std::sqrt(best2);
  }

 private:
  // min(best2, squared distances from point self to the other points in [begin, end)).
  double nearestIn(Eigen::Index self, Eigen::Index begin, Eigen::Index end, double best2) const {
    const Vec<Dim> p = sorted_.col(self);
    for (Eigen::Index s = begin; s < end; ++s)
      if (s != self) best2 = std::min(best2, (sorted_.col(s) - p).squaredNorm());
    return best2;
  }

  // min(best2, squared distances from point self to the points of the cells at Chebyshev
  // distance `ring` from its cell c, within the grid).
  double nearestInRing(Eigen::Index self, const Cell<Dim>& c, std::int64_t ring, double best2) const {
    Cell<Dim> lower, upper;
    for (int k = 0; k < Dim; ++k) {
      lower[k] = std::max<std::int64_t>(0, c[k] - ring);
      upper[k] = std::min(maxCell_[k], c[k] + ring);
    }
    Cell<Dim> q = lower;
    while (true) {
      std::int64_t chebyshev = 0;
      for (int k = 0; k < Dim; ++k) chebyshev = std::max(chebyshev, std::abs(q[k] - c[k]));
      if (chebyshev == ring) {
        if (const FlatCellMap::Slot* cell = cells_.find(keyOf<Dim>(q))) best2 = nearestIn(self, cell->begin, cell->end, best2);
      }
      int k = 0;
      for (; k < Dim; ++k) {
        if (q[k] < upper[k]) {
          ++q[k];
          break;
        }
        q[k] = lower[k];
      }
      if (k == Dim) return best2;
    }
  }

  Vec<Dim> lo_;
  double cell_;
  Points<Dim> sorted_;
  FlatCellMap cells_;  // key → [begin, end) in sorted_
  Cell<Dim> maxCell_;
};

// Throws for a non-finite coordinate or normal or a zero normal; scales every normal to unit length.
template <int Dim>
void normalizeNormals(const Points<Dim>& P, Points<Dim>& N, const std::string& source) {
  for (Eigen::Index i = 0; i < P.cols(); ++i) {
    // Built only for a message: a string for every sample would slow down large clouds.
    const auto sample = [&] { return source + ": sample " + std::to_string(i) + ": "; };
    if (!P.col(i).allFinite()) throw InputError(sample() + "non-finite coordinate " + formatVector<Dim>(P.col(i)));
    if (!N.col(i).allFinite()) throw InputError(sample() + "non-finite normal " + formatVector<Dim>(N.col(i)));
    // Scaling by the largest component first keeps tiny and huge normals from under/overflowing.
    const double largest = N.col(i).cwiseAbs().maxCoeff();
    if (largest == 0) throw InputError(sample() + "normal is zero");
    const Vec<Dim> scaled = N.col(i) / largest;
    N.col(i) = scaled / scaled.norm();
  }
}

// Exact duplicates found in runs of equal points: each but the first of a run, with one
// example pair for the warning.
struct Duplicates {
  std::vector<char> removed;  // one per sample, 1 for a repeat
  Eigen::Index count = 0;
  Eigen::Index exampleKept = -1, exampleRemoved = -1;
};

// The repeats of earlier samples (`order`: P's lexicographicOrder); throws when a repeat's
// normal differs from its first's.
template <int Dim>
Duplicates findDuplicates(const Points<Dim>& P, const Points<Dim>& N, const std::string& source,
                          const std::vector<Eigen::Index>& order) {
  constexpr double kNormalTolerance = 1e-12;
  Duplicates d;
  d.removed.assign(static_cast<std::size_t>(P.cols()), 0);
  for (std::size_t s = 0; s < order.size();) {
    std::size_t e = s + 1;
    const Eigen::Index first = order[s];
    while (e < order.size() && P.col(order[e]) == P.col(first)) {
      const Eigen::Index j = order[e];
      if ((N.col(j) - N.col(first)).cwiseAbs().maxCoeff() > kNormalTolerance)
        throw InputError(source + ": samples " + std::to_string(first) + " and " + std::to_string(j) +
                         " are at the same point " + formatVector<Dim>(P.col(first)) +
                         " but have different normals " + formatVector<Dim>(N.col(first)) + " and " +
                         formatVector<Dim>(N.col(j)));
      d.removed[j] = 1;
      if (d.count == 0) d.exampleKept = first, d.exampleRemoved = j;
      ++d.count;
      ++e;
    }
    s = e;
  }
  return d;
}

// Drops the removed samples, keeping the order of the rest; returns how many remain.
template <int Dim>
Eigen::Index removeSamples(Points<Dim>& P, Points<Dim>& N, const std::vector<char>& removed) {
  Eigen::Index out = 0;
  for (Eigen::Index i = 0; i < P.cols(); ++i) {
    if (removed[i]) continue;
    if (out != i) {
      P.col(out) = P.col(i);
      N.col(out) = N.col(i);
    }
    ++out;
  }
  P.conservativeResize(Eigen::NoChange, out);
  N.conservativeResize(Eigen::NoChange, out);
  return out;
}

}  // namespace

template <int Dim>
void validateSamples(HermiteSamples<Dim>& samples, std::vector<std::string>& warnings, const std::string& source,
                     const std::vector<Eigen::Index>* order) {
  Points<Dim>& P = samples.points;
  Points<Dim>& N = samples.normals;
  if (P.cols() != N.cols())
    throw InputError(source + ": " + std::to_string(P.cols()) + " points but " +
                     std::to_string(N.cols()) + " normals (one normal per point)");
  normalizeNormals<Dim>(P, N, source);
  const std::vector<Eigen::Index> own = order ? std::vector<Eigen::Index>{} : lexicographicOrder<Dim>(P);
  const Duplicates d = findDuplicates<Dim>(P, N, source, order ? *order : own);
  if (d.count == 0) return;
  const Eigen::Index remaining = removeSamples<Dim>(P, N, d.removed);
  warnings.push_back(source + ": merged " + std::to_string(d.count) + " exact duplicate sample" +
                     (d.count == 1 ? "" : "s") + " (e.g. sample " + std::to_string(d.exampleRemoved) +
                     " repeats sample " + std::to_string(d.exampleKept) + "); " + std::to_string(remaining) +
                     " samples remain");
}

template <int Dim>
double meanSampleSpacing(const Points<Dim>& points) {
  const Eigen::Index n = points.cols();
  if (n < 2) return 0.0;

  const Vec<Dim> lo = points.rowwise().minCoeff();
  const Vec<Dim> extent = points.rowwise().maxCoeff() - lo;
  const double largest = extent.maxCoeff();
  if (largest == 0) return 0.0;  // all points coincide

  const double cell = spacingCellSize<Dim>(points, lo, extent, largest / kMaxCellsPerAxis);
  const CellIndex<Dim> index(points, lo, extent, cell);
  std::vector<double> nearest(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(dynamic, 1024)
  for (Eigen::Index self = 0; self < n; ++self) nearest[self] = index.nearestDistance(self);
  // Summed in a fixed order so the result does not depend on the thread count.
  double sum = 0;
  for (double d : nearest) sum += d;
  return sum / double(n);
}

template void validateSamples<2>(HermiteSamples<2>&, std::vector<std::string>&, const std::string&,
                                 const std::vector<Eigen::Index>*);
template void validateSamples<3>(HermiteSamples<3>&, std::vector<std::string>&, const std::string&,
                                 const std::vector<Eigen::Index>*);
template double meanSampleSpacing<2>(const Points<2>&);
template double meanSampleSpacing<3>(const Points<3>&);

template <int Dim>
HermiteSamples<Dim> withoutSample(const HermiteSamples<Dim>& samples, int i) {
  const int N = samples.size();
  HermiteSamples<Dim> rest;
  rest.points.resize(Dim, N - 1);
  rest.normals.resize(Dim, N - 1);
  for (int j = 0, k = 0; j < N; ++j) {
    if (j == i) continue;
    rest.points.col(k) = samples.points.col(j);
    rest.normals.col(k++) = samples.normals.col(j);
  }
  return rest;
}

template HermiteSamples<2> withoutSample<2>(const HermiteSamples<2>&, int);
template HermiteSamples<3> withoutSample<3>(const HermiteSamples<3>&, int);

}  // namespace hermite
