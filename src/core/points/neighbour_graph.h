#pragma once
// The k-nearest-neighbour graph of a point cloud (nanoflann's k-d tree over the columns), shared by
// normal estimation's sheet fits and its orientation (normal_estimation.h).

#include <cstdint>
#include <vector>

#include <nanoflann.hpp>

#include "core/base/geometry.h"

namespace hermite::detail {

// nanoflann's dataset interface over a Dim × N column matrix.
template <int Dim>
struct CloudAdaptor {
  const Points<Dim>& P;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(P.cols()); }
  double kdtree_get_pt(std::size_t i, std::size_t k) const { return P(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(i)); }
  template <class B>
  bool kdtree_get_bbox(B&) const { return false; }
};

template <int Dim>
using KdTree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, CloudAdaptor<Dim>>,
                                                   CloudAdaptor<Dim>, Dim, std::uint32_t>;

// The symmetric k-nearest-neighbour graph: `nbr` holds each point's k nearest (itself included,
// row-major N × k), `reverse` the points that list it.
struct NeighbourGraph {
  int k = 0;
  std::vector<std::uint32_t> nbr;
  std::vector<std::vector<std::uint32_t>> reverse;
  const std::uint32_t* of(int i) const { return nbr.data() + static_cast<std::size_t>(i) * k; }
};

// Each point's k nearest neighbours (fewer points: the point itself fills the row).
template <int Dim>
NeighbourGraph neighbourGraph(const Points<Dim>& points, int k);

}  // namespace hermite::detail
