#include "core/mesh/occupied_cells.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace hermite {

namespace {

constexpr int kAxisBits = 21;
constexpr std::int64_t kAxisOffset = std::int64_t{1} << (kAxisBits - 1);  // index 0 sits mid-range
constexpr std::uint64_t kAxisMask = (std::uint64_t{1} << kAxisBits) - 1;
constexpr std::uint64_t kEmpty = ~std::uint64_t{0};  // no packed key has all 64 bits set

std::uint64_t pack(std::int64_t i, std::int64_t j, std::int64_t k) {
  const auto axis = [](std::int64_t c) {
    return static_cast<std::uint64_t>(std::clamp<std::int64_t>(c + kAxisOffset, 0, kAxisMask));
  };
  return axis(i) | axis(j) << kAxisBits | axis(k) << (2 * kAxisBits);
}

// The cell index of each coordinate, clamped to the keys' range first (a point beyond it shares
// the outermost cells: a false "near", never a false "far").
std::array<std::int64_t, 3> cellIndex(const Vec<3>& x, const Vec<3>& origin, double cell) {
  std::array<std::int64_t, 3> c{};
  const double limit = static_cast<double>(kAxisOffset);
  for (int a = 0; a < 3; ++a)
    c[a] = static_cast<std::int64_t>(std::clamp(std::floor((x[a] - origin[a]) / cell), -limit, limit));
  return c;
}

// Mixes a packed key over all bits (the multiplier of Fibonacci hashing).
std::uint64_t slotHash(std::uint64_t key) { return (key * 0x9E3779B97F4A7C15ULL) >> 17; }

}  // namespace

OccupiedCells::OccupiedCells(const Points<3>& samples, const Vec<3>& origin, double cell)
    : samples_(samples), origin_(origin), cell_(cell) {
  std::size_t capacity = 16;
  while (capacity < 2 * static_cast<std::size_t>(samples.cols())) capacity *= 2;
  slots_.assign(capacity, kEmpty);
  first_.assign(capacity, -1);
  next_.assign(static_cast<std::size_t>(samples.cols()), -1);
  mask_ = capacity - 1;
  for (Eigen::Index i = 0; i < samples.cols(); ++i) {
    const std::uint64_t s = insert(keyOf(samples.col(i)));
    next_[static_cast<std::size_t>(i)] = first_[s];
    first_[s] = static_cast<int>(i);
  }
}

std::uint64_t OccupiedCells::keyOf(const Vec<3>& x) const {
  const std::array<std::int64_t, 3> c = cellIndex(x, origin_, cell_);
  return pack(c[0], c[1], c[2]);
}

std::uint64_t OccupiedCells::insert(std::uint64_t key) {
  for (std::uint64_t s = slotHash(key) & mask_;; s = (s + 1) & mask_) {
    if (slots_[s] == key) return s;
    if (slots_[s] == kEmpty) {
      slots_[s] = key;
      return s;
    }
  }
}

std::int64_t OccupiedCells::slotOf(std::uint64_t key) const {
  for (std::uint64_t s = slotHash(key) & mask_;; s = (s + 1) & mask_) {
    if (slots_[s] == key) return static_cast<std::int64_t>(s);
    if (slots_[s] == kEmpty) return -1;
  }
}

bool OccupiedCells::farFromSamples(const Vec<3>& x) const {
  const auto [i, j, k] = cellIndex(x, origin_, cell_);
  if (slotOf(pack(i, j, k)) >= 0) return false;  // the usual answer, in one probe
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if (slotOf(pack(i + dx, j + dy, k + dz)) >= 0) return false;
  return true;
}

// Appends the samples of the cell with key `key` within r of x to `out`, up to `limit` (0: all);
// whether the limit is reached.
bool OccupiedCells::cellSamplesWithin(std::uint64_t key, const Vec<3>& x, double r, std::vector<int>& out,
                                      int limit) const {
  const std::int64_t s = slotOf(key);
  for (int p = s >= 0 ? first_[static_cast<std::size_t>(s)] : -1; p >= 0; p = next_[static_cast<std::size_t>(p)]) {
    if ((samples_.col(p) - x).squaredNorm() > r * r) continue;
    out.push_back(p);
    if (limit > 0 && static_cast<int>(out.size()) >= limit) return true;
  }
  return false;
}

void OccupiedCells::samplesWithin(const Vec<3>& x, double r, std::vector<int>& out, int limit) const {
  out.clear();
  // x's own cell first: with a limit it usually answers alone.
  const std::uint64_t own = keyOf(x);
  if (cellSamplesWithin(own, x, r, out, limit)) return;
  const std::array<std::int64_t, 3> lo = cellIndex(x - Vec<3>::Constant(r), origin_, cell_);
  const std::array<std::int64_t, 3> hi = cellIndex(x + Vec<3>::Constant(r), origin_, cell_);
  for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
    for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
      for (std::int64_t i = lo[0]; i <= hi[0]; ++i) {
        const std::uint64_t key = pack(i, j, k);
        if (key != own && cellSamplesWithin(key, x, r, out, limit)) return;
      }
}

}  // namespace hermite
