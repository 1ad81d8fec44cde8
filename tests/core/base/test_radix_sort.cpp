#include "core/base/radix_sort.h"

#include <algorithm>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <omp.h>

namespace {

// Restores the OpenMP thread count a test changes.
struct ThreadCount {
  int saved = omp_get_max_threads();
  ~ThreadCount() { omp_set_num_threads(saved); }
};

// radixSort(v) equals std::sort with std::less, element for element.
template <class T>
void checkLikeStdSort(std::vector<T> v) {
  std::vector<T> expected = v;
  std::sort(expected.begin(), expected.end());
  hermite::radixSort(v);
  CHECK(v == expected);
}

}  // namespace

TEST_CASE("radixSort equals std::sort for integers and pairs of integers") {
  const ThreadCount restore;
  std::mt19937_64 rng(17);
  const std::size_t big = 5 * hermite::detail::kRadixMinSize + 3;
  for (int threads : {1, 2, 3, 8}) {
    omp_set_num_threads(threads);
    // Empty, below the radix size (std::sort), and parts of unequal length.
    for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(1000), big}) {
      CAPTURE(threads);
      CAPTURE(n);
      std::vector<std::uint64_t> u(n);  // small keys with duplicates: few passes
      for (auto& x : u) x = rng() % 5000;
      checkLikeStdSort(u);
      for (auto& x : u) x = rng();  // every digit differs: all six passes, the top one of 9 bits
      checkLikeStdSort(u);
      std::vector<std::int64_t> s(n);  // negative and positive: the sign bit orders them
      for (auto& x : s) x = static_cast<std::int64_t>(rng() % 2001) - 1000;
      checkLikeStdSort(s);
      std::vector<std::pair<std::int64_t, int>> p(n);  // by first, then second, both signed
      for (auto& x : p) x = {static_cast<std::int64_t>(rng() % 41) - 20, static_cast<int>(rng() % 2001) - 1000};
      checkLikeStdSort(p);
      std::vector<std::pair<std::uint64_t, long>> q(n);
      for (auto& x : q) x = {rng() >> 20, static_cast<long>(rng() % 7)};
      checkLikeStdSort(q);
    }
  }
}

TEST_CASE("radixSort of equal keys, and inside a parallel region") {
  std::vector<std::uint64_t> same(3 * hermite::detail::kRadixMinSize, 42);  // no pass at all
  hermite::radixSort(same);
  CHECK(std::all_of(same.begin(), same.end(), [](std::uint64_t x) { return x == 42; }));
  std::vector<std::vector<std::int64_t>> lists(4);
  for (std::size_t l = 0; l < lists.size(); ++l)
    for (int i = 0; i < 100000; ++i) lists[l].push_back((i * 7919 + static_cast<int>(l)) % 100003 - 50000);
#pragma omp parallel for
  for (int l = 0; l < 4; ++l) hermite::radixSort(lists[static_cast<std::size_t>(l)]);
  for (const auto& v : lists) CHECK(std::is_sorted(v.begin(), v.end()));
}
