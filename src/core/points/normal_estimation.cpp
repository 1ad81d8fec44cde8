#include "core/points/normal_estimation.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <vector>

#include <Eigen/Eigenvalues>
#include <nanoflann.hpp>

#include "core/base/errors.h"

namespace hermite {

namespace {

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

}  // namespace

template <int Dim>
Points<Dim> estimateNormals(const Points<Dim>& points, const NormalEstimationOptions& options) {
  const int n = static_cast<int>(points.cols());
  if (n < 2) throw InputError("normal estimation: needs at least 2 points (got " + std::to_string(n) + ")");
  const int k = std::min(std::max(options.neighbours, Dim), n);
  CloudAdaptor<Dim> cloud{points};
  KdTree<Dim> tree(Dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  // k nearest neighbours of every point (the point itself included), row-major n × k.
  std::vector<std::uint32_t> nbr(static_cast<std::size_t>(n) * k);
  Points<Dim> normals(Dim, n);
#pragma omp parallel
  {
    std::vector<double> d2(static_cast<std::size_t>(k));
#pragma omp for schedule(dynamic, 1024)
    for (int i = 0; i < n; ++i) {
      std::uint32_t* idx = nbr.data() + static_cast<std::size_t>(i) * k;
      const Vec<Dim> p = points.col(i);
      const std::size_t found = tree.knnSearch(p.data(), static_cast<std::size_t>(k), idx, d2.data());
      for (std::size_t j = found; j < static_cast<std::size_t>(k); ++j) idx[j] = static_cast<std::uint32_t>(i);
      Vec<Dim> mean = Vec<Dim>::Zero();
      for (int j = 0; j < k; ++j) mean += points.col(idx[j]);
      mean /= k;
      Mat<Dim> C = Mat<Dim>::Zero();
      for (int j = 0; j < k; ++j) {
        const Vec<Dim> d = points.col(idx[j]) - mean;
        C += d * d.transpose();
      }
      Eigen::SelfAdjointEigenSolver<Mat<Dim>> eig(C);
      Vec<Dim> nrm = eig.eigenvectors().col(0);  // smallest eigenvalue first
      if (!(nrm.norm() > 0) || !nrm.allFinite()) nrm = Vec<Dim>::UnitX();
      normals.col(i) = nrm.normalized();
    }
  }

  // Orientation: Prim's minimum spanning tree over the symmetric k-NN graph, cost 1 − |nᵢ·nⱼ|;
  // each tree edge copies the parent's orientation to the child.
  std::vector<std::vector<std::uint32_t>> reverse(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) {
      const std::uint32_t o = nbr[static_cast<std::size_t>(i) * k + j];
      if (static_cast<int>(o) != i) reverse[o].push_back(static_cast<std::uint32_t>(i));
    }
  std::vector<char> done(static_cast<std::size_t>(n), 0);
  using Item = std::pair<double, std::pair<std::uint32_t, std::uint32_t>>;  // cost, (child, parent)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  std::vector<int> component;
  for (int seed = 0; seed < n; ++seed) {
    if (done[seed]) continue;
    component.clear();
    done[seed] = 1;
    component.push_back(seed);
    auto push = [&](std::uint32_t from) {
      auto edge = [&](std::uint32_t to) {
        if (done[to]) return;
        heap.push({1.0 - std::abs(normals.col(from).dot(normals.col(to))), {to, from}});
      };
      for (int j = 0; j < k; ++j) edge(nbr[static_cast<std::size_t>(from) * k + j]);
      for (std::uint32_t to : reverse[from]) edge(to);
    };
    push(static_cast<std::uint32_t>(seed));
    while (!heap.empty()) {
      const auto [cost, e] = heap.top();
      heap.pop();
      const auto [child, parent] = e;
      if (done[child]) continue;
      done[child] = 1;
      if (normals.col(child).dot(normals.col(parent)) < 0) normals.col(child) = -normals.col(child);
      component.push_back(static_cast<int>(child));
      push(child);
    }
    // Outward: the component's farthest sample from its centroid points away from it.
    Vec<Dim> centroid = Vec<Dim>::Zero();
    for (int i : component) centroid += points.col(i);
    centroid /= static_cast<double>(component.size());
    int far = component.front();
    double farD = -1;
    for (int i : component) {
      const double d = (points.col(i) - centroid).squaredNorm();
      if (d > farD) {
        farD = d;
        far = i;
      }
    }
    if (normals.col(far).dot(points.col(far) - centroid) < 0)
      for (int i : component) normals.col(i) = -normals.col(i);
  }
  return normals;
}

template Points<2> estimateNormals<2>(const Points<2>&, const NormalEstimationOptions&);
template Points<3> estimateNormals<3>(const Points<3>&, const NormalEstimationOptions&);

}  // namespace hermite
