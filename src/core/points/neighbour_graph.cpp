#include "core/points/neighbour_graph.h"

namespace hermite::detail {

template <int Dim>
NeighbourGraph neighbourGraph(const Points<Dim>& points, int k) {
  const int n = static_cast<int>(points.cols());
  NeighbourGraph g;
  g.k = k;
  g.nbr.resize(static_cast<std::size_t>(n) * k);
  CloudAdaptor<Dim> cloud{points};
  KdTree<Dim> tree(Dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
#pragma omp parallel
  {
    std::vector<double> d2(static_cast<std::size_t>(k));
#pragma omp for schedule(dynamic, 1024)
    for (int i = 0; i < n; ++i) {
      std::uint32_t* idx = g.nbr.data() + static_cast<std::size_t>(i) * k;
      const Vec<Dim> p = points.col(i);
      const std::size_t found = tree.knnSearch(p.data(), static_cast<std::size_t>(k), idx, d2.data());
      for (std::size_t j = found; j < static_cast<std::size_t>(k); ++j) idx[j] = static_cast<std::uint32_t>(i);
    }
  }
  g.reverse.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) {
      const std::uint32_t o = g.of(i)[j];
      if (static_cast<int>(o) != i) g.reverse[o].push_back(static_cast<std::uint32_t>(i));
    }
  return g;
}

template NeighbourGraph neighbourGraph<2>(const Points<2>&, int);
template NeighbourGraph neighbourGraph<3>(const Points<3>&, int);

}  // namespace hermite::detail
