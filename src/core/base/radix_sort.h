#pragma once
// Least-significant-digit radix sort of integers, or of pairs of integers, on the OpenMP threads:
// the order std::sort gives with std::less (a pair by its first, then its second), in a few
// linear passes instead of n log n comparisons. Each pass is stable and moves the elements by one
// 11-bit digit of a key (the pair's second, then its first); a digit every element shares is
// skipped, so small keys (mesh edges, grid cells, triangle indices) take few passes. A pass on
// more than one thread splits the range into contiguous parts, counts each part's digits, and
// places every part after the parts before it, so it stays stable. Used for the key sorts of
// `mesh` (docs/performance.md, "Sorting keys by their digits").

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>
#include <vector>

#include <omp.h>

namespace hermite {

namespace detail {

inline constexpr int kRadixBits = 11;
inline constexpr std::size_t kRadixBuckets = std::size_t(1) << kRadixBits;
// Below this many elements std::sort is as fast, and gives the same order.
inline constexpr std::size_t kRadixMinSize = std::size_t(1) << 14;

// x as an unsigned number in the same order (signed: the sign bit flipped).
template <class I>
std::uint64_t radixOrderBits(I x) {
  static_assert(std::is_integral_v<I> && sizeof(I) <= 8, "radixSort sorts integers of at most 64 bits");
  if constexpr (std::is_signed_v<I>)
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(x)) ^ (std::uint64_t(1) << 63);
  else
    return static_cast<std::uint64_t>(x);
}

// The keys of an element, most significant first: the integer itself, or the pair's members.
template <class T>
struct RadixKeys {
  static constexpr int kCount = 1;
  static std::uint64_t key(const T& x, int) { return radixOrderBits(x); }
};
template <class A, class B>
struct RadixKeys<std::pair<A, B>> {
  static constexpr int kCount = 2;
  static std::uint64_t key(const std::pair<A, B>& x, int which) {
    return which == 0 ? radixOrderBits(x.first) : radixOrderBits(x.second);
  }
};

using RadixCounts = std::array<std::size_t, kRadixBuckets>;

// The digits (key, shift) on which the elements differ, least significant first: the passes
// the sort needs. A digit differs somewhere exactly where the keys' bitwise AND and OR do.
template <class T>
std::vector<std::pair<int, int>> radixPasses(const T* v, std::size_t n) {
  constexpr int K = RadixKeys<T>::kCount;
  std::array<std::uint64_t, K> differ{};  // per key: the bits on which some two elements differ
  for (int k = 0; k < K; ++k) {
    std::uint64_t a = ~std::uint64_t(0), o = 0;
#pragma omp parallel for reduction(& : a) reduction(| : o)
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t key = RadixKeys<T>::key(v[i], k);
      a &= key;
      o |= key;
    }
    differ[std::size_t(k)] = a ^ o;
  }
  std::vector<std::pair<int, int>> passes;
  for (int k = K - 1; k >= 0; --k)
    for (int shift = 0; shift < 64; shift += kRadixBits)
      if ((differ[std::size_t(k)] >> shift) & (kRadixBuckets - 1)) passes.emplace_back(k, shift);
  return passes;
}

// One stable pass from `in` to `out` (n elements) by the digit at `shift` of key `which`, on
// `parts` threads: each contiguous part counts its digits, then places its elements after those
// of the parts before it with the same digit.
template <class T>
void radixPass(const T* in, T* out, std::size_t n, int which, int shift, int parts) {
  std::vector<RadixCounts> at(static_cast<std::size_t>(parts));
  const auto digit = [&](const T& x) { return (RadixKeys<T>::key(x, which) >> shift) & (kRadixBuckets - 1); };
  const auto begin = [&](int p) { return n * static_cast<std::size_t>(p) / static_cast<std::size_t>(parts); };
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int p = 0; p < parts; ++p) {
    RadixCounts& c = at[static_cast<std::size_t>(p)];
    c.fill(0);
    for (std::size_t i = begin(p); i < begin(p + 1); ++i) ++c[digit(in[i])];
  }
  std::size_t next = 0;  // where the next (digit, part) run starts
  for (std::size_t d = 0; d < kRadixBuckets; ++d)
    for (RadixCounts& c : at) {
      const std::size_t size = c[d];
      c[d] = next;
      next += size;
    }
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int p = 0; p < parts; ++p) {
    RadixCounts& c = at[static_cast<std::size_t>(p)];
    for (std::size_t i = begin(p); i < begin(p + 1); ++i) out[c[digit(in[i])]++] = in[i];
  }
}

}  // namespace detail

// Sorts v ascending (std::less) by its integers' digits.
template <class T>
void radixSort(std::vector<T>& v) {
  const std::size_t n = v.size();
  if (n < detail::kRadixMinSize) return std::sort(v.begin(), v.end());
  const int parts = omp_in_parallel() ? 1 : std::max(1, omp_get_max_threads());
  std::vector<T> buffer(n);
  T* in = v.data();
  T* out = buffer.data();
  for (const auto& [which, shift] : detail::radixPasses(in, n)) {
    detail::radixPass(in, out, n, which, shift, parts);
    std::swap(in, out);
  }
  if (in != v.data()) v.swap(buffer);
}

}  // namespace hermite
