#include "core/base/parallel_sort.h"

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

}  // namespace

TEST_CASE("parallelSort equals std::sort element for element") {
  const ThreadCount restore;
  std::mt19937_64 rng(17);
  for (int threads : {1, 2, 3, 4, 8}) {
    omp_set_num_threads(threads);
    // Below one part, one part per thread, and parts of unequal length (odd sizes).
    for (std::ptrdiff_t n : {std::ptrdiff_t(0), std::ptrdiff_t(1), std::ptrdiff_t(1000),
                             4 * hermite::kParallelSortMinPart + 3, 9 * hermite::kParallelSortMinPart + 1}) {
      CAPTURE(threads);
      CAPTURE(n);
      std::vector<std::uint64_t> keys(static_cast<std::size_t>(n));
      for (auto& k : keys) k = rng() % 5000;  // many duplicates: equal keys are indistinguishable
      std::vector<std::uint64_t> expected = keys;
      std::sort(expected.begin(), expected.end());
      hermite::parallelSort(keys.begin(), keys.end());
      CHECK(keys == expected);
      // Pairs ordered by key then index (a strict total order), with a comparator.
      std::vector<std::pair<std::uint64_t, int>> pairs(static_cast<std::size_t>(n));
      for (std::size_t i = 0; i < pairs.size(); ++i) pairs[i] = {rng() % 5000, static_cast<int>(i)};
      std::vector<std::pair<std::uint64_t, int>> want = pairs;
      const auto byKeyDescending = [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second < b.second;
      };
      std::sort(want.begin(), want.end(), byKeyDescending);
      hermite::parallelSort(pairs.begin(), pairs.end(), byKeyDescending);
      CHECK(pairs == want);
    }
  }
}

TEST_CASE("parallelSort inside a parallel region sorts on the calling thread") {
  std::vector<std::vector<int>> lists(4);
  for (std::size_t l = 0; l < lists.size(); ++l)
    for (int i = 0; i < 100000; ++i) lists[l].push_back((i * 7919 + static_cast<int>(l)) % 100003);
#pragma omp parallel for
  for (int l = 0; l < 4; ++l) hermite::parallelSort(lists[static_cast<std::size_t>(l)].begin(), lists[static_cast<std::size_t>(l)].end());
  for (const auto& v : lists) CHECK(std::is_sorted(v.begin(), v.end()));
}
