#pragma once
// std::sort on the OpenMP threads: the range in 2^k parts (2^k ≤ the thread count, each part at
// least kParallelSortMinPart elements), each sorted on its own thread, then merged pairwise in
// parallel through one buffer. With a strict total order (no two elements equivalent) the
// result equals std::sort's element for element; callers rely on that (their keys carry a
// tie-breaking index or are unique). For orders a comparator defines; integer keys sort faster
// by their digits (radix_sort.h).

#include <algorithm>
#include <cstddef>
#include <functional>
#include <iterator>
#include <vector>

#include <omp.h>

namespace hermite {

inline constexpr std::ptrdiff_t kParallelSortMinPart = 1 << 15;

template <class It, class Less>
void parallelSort(It first, It last, Less less) {
  using T = typename std::iterator_traits<It>::value_type;
  const std::ptrdiff_t n = last - first;
  int parts = 1;
  while (2 * parts <= omp_get_max_threads() && n / (2 * parts) >= kParallelSortMinPart) parts *= 2;
  if (parts == 1 || omp_in_parallel()) return std::sort(first, last, less);
  std::vector<std::ptrdiff_t> bound(static_cast<std::size_t>(parts) + 1);
  for (int p = 0; p <= parts; ++p) bound[static_cast<std::size_t>(p)] = n * p / parts;
#pragma omp parallel for schedule(static, 1) num_threads(parts)
  for (int p = 0; p < parts; ++p)
    std::sort(first + bound[static_cast<std::size_t>(p)], first + bound[static_cast<std::size_t>(p) + 1], less);
  std::vector<T> buffer(static_cast<std::size_t>(n));
  // Runs of `width` parts are sorted; merge neighbouring runs into the buffer, then copy back.
  for (int width = 1; width < parts; width *= 2) {
    const int merges = parts / (2 * width);
#pragma omp parallel for schedule(static, 1) num_threads(merges)
    for (int m = 0; m < merges; ++m) {
      const std::ptrdiff_t a = bound[static_cast<std::size_t>(2 * m * width)];
      const std::ptrdiff_t b = bound[static_cast<std::size_t>((2 * m + 1) * width)];
      const std::ptrdiff_t c = bound[static_cast<std::size_t>((2 * m + 2) * width)];
      std::merge(std::make_move_iterator(first + a), std::make_move_iterator(first + b),
                 std::make_move_iterator(first + b), std::make_move_iterator(first + c), buffer.begin() + a, less);
      std::move(buffer.begin() + a, buffer.begin() + c, first + a);
    }
  }
}

template <class It>
void parallelSort(It first, It last) {
  parallelSort(first, last, std::less<>());
}

}  // namespace hermite
