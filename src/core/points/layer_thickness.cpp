#include "core/points/layer_thickness.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <Eigen/Eigenvalues>

#include "core/points/neighbour_graph.h"

namespace hermite {

namespace {

// The relative thickness of the k nearest other points of `probe` (a point of `cloud`, which
// the tree indexes): idx and d2 hold k + 1 entries.
template <int Dim>
double thicknessAt(const Points<Dim>& cloud, const detail::KdTree<Dim>& tree, const Vec<Dim>& probe,
                   std::vector<std::uint32_t>& idx, std::vector<double>& d2) {
  const std::size_t found = tree.knnSearch(probe.data(), idx.size(), idx.data(), d2.data());
  const int m = int(found) - 1;  // the nearest is the probe itself
  if (m < Dim + 1) return 0;
  Vec<Dim> mean = Vec<Dim>::Zero();
  double reach = 0;
  for (std::size_t j = 1; j < found; ++j) {
    mean += cloud.col(idx[j]);
    reach += std::sqrt(d2[j]);
  }
  if (!(reach > 0)) return 0;
  mean /= m;
  Mat<Dim> cov = Mat<Dim>::Zero();
  for (std::size_t j = 1; j < found; ++j) {
    const Vec<Dim> d = cloud.col(idx[j]) - mean;
    cov += d * d.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Mat<Dim>> eig(cov / m, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, eig.eigenvalues()(0))) / (reach / m);
}

}  // namespace

template <int Dim>
LayerThickness layerThickness(const Points<Dim>& points, const LayerThicknessOptions& options) {
  const Eigen::Index n = points.cols();
  const int k = std::max(options.neighbours, Dim);
  LayerThickness out;
  if (n < k + 1) return out;
  const Eigen::Index stride = std::max<Eigen::Index>(1, n / std::max(options.maxTree, k + 1));
  Points<Dim> cloud(Dim, (n + stride - 1) / stride);
  for (Eigen::Index i = 0, c = 0; i < n; i += stride) cloud.col(c++) = points.col(i);
  const detail::CloudAdaptor<Dim> adaptor{cloud};
  const detail::KdTree<Dim> tree(Dim, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  const Eigen::Index m = cloud.cols(), step = std::max<Eigen::Index>(1, m / std::max(options.maxProbes, 1));
  std::vector<double> thickness(static_cast<std::size_t>((m + step - 1) / step));
#pragma omp parallel
  {
    std::vector<std::uint32_t> idx(static_cast<std::size_t>(k + 1));
    std::vector<double> d2(static_cast<std::size_t>(k + 1));
#pragma omp for schedule(static)
    for (Eigen::Index p = 0; p < Eigen::Index(thickness.size()); ++p)
      thickness[std::size_t(p)] = thicknessAt<Dim>(cloud, tree, cloud.col(p * step), idx, d2);
  }
  std::nth_element(thickness.begin(), thickness.begin() + thickness.size() / 2, thickness.end());
  out.median = thickness[thickness.size() / 2];
  out.probes = int(thickness.size());
  return out;
}

template LayerThickness layerThickness<2>(const Points<2>&, const LayerThicknessOptions&);
template LayerThickness layerThickness<3>(const Points<3>&, const LayerThicknessOptions&);

}  // namespace hermite
