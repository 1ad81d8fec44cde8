#include "core/points/lexicographic_order.h"

#include <array>

#include "core/base/parallel_sort.h"

namespace hermite {

// The coordinates are copied next to their index so that the sort compares contiguous keys
// instead of chasing indices.
template <int Dim>
std::vector<Eigen::Index> lexicographicOrder(const Points<Dim>& P) {
  struct Key {
    std::array<double, Dim> p;
    Eigen::Index index;
  };
  const Eigen::Index n = P.cols();
  std::vector<Key> keys(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    Key& k = keys[static_cast<std::size_t>(i)];
    for (int c = 0; c < Dim; ++c) k.p[static_cast<std::size_t>(c)] = P(c, i);
    k.index = i;
  }
  parallelSort(keys.begin(), keys.end(), [](const Key& a, const Key& b) {
    for (std::size_t c = 0; c < Dim; ++c) {
      if (a.p[c] < b.p[c]) return true;
      if (b.p[c] < a.p[c]) return false;
    }
    return a.index < b.index;
  });
  std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
  for (std::size_t i = 0; i < keys.size(); ++i) order[i] = keys[i].index;
  return order;
}

template std::vector<Eigen::Index> lexicographicOrder<2>(const Points<2>&);
template std::vector<Eigen::Index> lexicographicOrder<3>(const Points<3>&);

}  // namespace hermite
