#include "core/points/normal_estimation.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/points/fold_normals.h"
#include "core/points/neighbour_graph.h"
#include "core/points/normal_orientation.h"
#include "core/points/sheet_fit.h"

namespace hermite {

using detail::CloudAdaptor;
using detail::EdgeKind;
using detail::EdgeRule;
using detail::KdTree;
using detail::NeighbourGraph;
using detail::edgeRule;
using detail::betweenSheets;
using detail::foldNormals;
using detail::followGivenMajority;
using detail::neighbourGraph;
using detail::orientNormals;
using detail::sheetBands;
using detail::sheetNormal;

template <int Dim>
int completeNormals(const Points<Dim>& points, Points<Dim>& normals, const NormalEstimationOptions& options) {
  const int n = static_cast<int>(points.cols());
  std::vector<char> known(static_cast<std::size_t>(n));
  int missing = 0;
  for (int i = 0; i < n; ++i) {
    known[i] = normals.col(i).isZero(0) ? 0 : 1;
    missing += 1 - known[i];
  }
  if (missing == 0) return 0;
  if (n < 2)
    throw InputError("normal estimation: needs at least 2 points (got " + std::to_string(n) + ")");
  const int k = std::min(std::max(options.neighbours, Dim), n);
  const NeighbourGraph g = neighbourGraph<Dim>(points, k);
  const std::vector<double> band = sheetBands<Dim>(points, g, options.sheetBand);
  Points<Dim> second = Points<Dim>::Zero(Dim, n);  // per point: its second sheet's offset × normal
#pragma omp parallel for schedule(dynamic, 1024)
  for (int i = 0; i < n; ++i)
    if (!known[i]) {
      Vec<Dim> c;
      normals.col(i) = sheetNormal<Dim>(points, g, i, band[i], c);
      second.col(i) = c;
    }
  // Estimated lines of samples between two sheets (a rim's) take the sheets' line: no bridge.
  const std::vector<char> between = betweenSheets<Dim>(points, normals, g, band);
  orientNormals<Dim>(points, normals, known, g, band, second, options, nullptr, &between);
  foldNormals<Dim>(points, normals, known, g, band, options.sheetBand);
  return missing;
}

template <int Dim>
double orientationDisagreement(const Points<Dim>& points, const Points<Dim>& normals,
                               const NormalEstimationOptions& options) {
  const int n = static_cast<int>(points.cols());
  if (n < 2) return 0;
  const int k = std::min(std::max(options.neighbours, Dim), n);
  // At most 50 000 evenly strided points query their neighbours (the tree holds all): a loader
  // runs this on every file with normals, and the fraction needs no more.
  const int stride = std::max(1, n / 50000);
  CloudAdaptor<Dim> cloud{points};
  KdTree<Dim> tree(Dim, cloud, nanoflann::KDTreeSingleIndexAdaptorParams(16));
  const double inf = std::numeric_limits<double>::infinity();
  long edges = 0, flips = 0;  // edges along a sheet, and those whose normals point opposite ways
#pragma omp parallel reduction(+ : edges, flips)
  {
    std::vector<std::uint32_t> idx(static_cast<std::size_t>(k));
    std::vector<double> d2(static_cast<std::size_t>(k));
#pragma omp for schedule(dynamic, 256)
    for (int i = 0; i < n; i += stride) {
      if (normals.col(i).isZero(0)) continue;
      const Vec<Dim> p = points.col(i);
      const std::size_t found = tree.knnSearch(p.data(), static_cast<std::size_t>(k), idx.data(), d2.data());
      for (std::size_t j = 0; j < found; ++j) {
        const int o = static_cast<int>(idx[j]);
        if (o == i || normals.col(o).isZero(0)) continue;
        const EdgeRule r = edgeRule<Dim>(points, normals, i, o, options, inf, inf, Vec<Dim>::Zero(), Vec<Dim>::Zero());  // angles only
        if (r.kind != EdgeKind::Along) continue;  // creases and gaps: noise makes their rules unsure
        ++edges;
        flips += r.flip;
      }
    }
  }
  return edges == 0 ? 0.0 : double(flips) / double(edges);
}

template <int Dim>
int orientNormalLines(const Points<Dim>& points, Points<Dim>& normals, const NormalEstimationOptions& options) {
  const int n = static_cast<int>(points.cols());
  for (int i = 0; i < n; ++i)
    if (normals.col(i).isZero(0))
      throw InputError("normal orientation: normal " + std::to_string(i) + " is zero (estimate it first)");
  if (n < 2) return 0;
  const NeighbourGraph g = neighbourGraph<Dim>(points, std::min(std::max(options.neighbours, Dim), n));
  const Points<Dim> given = normals;
  std::vector<int> part(static_cast<std::size_t>(n), -1);
  orientNormals<Dim>(points, normals, std::vector<char>(static_cast<std::size_t>(n), 0), g,
                     sheetBands<Dim>(points, g, options.sheetBand), Points<Dim>::Zero(Dim, n), options, &part);
  followGivenMajority<Dim>(normals, given, part);
  int flipped = 0;
  for (int i = 0; i < n; ++i) flipped += normals.col(i).dot(given.col(i)) < 0;
  return flipped;
}

template <int Dim>
Points<Dim> estimateNormals(const Points<Dim>& points, const NormalEstimationOptions& options) {
  const int n = static_cast<int>(points.cols());
  if (n < 2) throw InputError("normal estimation: needs at least 2 points (got " + std::to_string(n) + ")");
  Points<Dim> normals = Points<Dim>::Zero(Dim, n);
  completeNormals<Dim>(points, normals, options);
  return normals;
}

template Points<2> estimateNormals<2>(const Points<2>&, const NormalEstimationOptions&);
template Points<3> estimateNormals<3>(const Points<3>&, const NormalEstimationOptions&);
template int completeNormals<2>(const Points<2>&, Points<2>&, const NormalEstimationOptions&);
template int completeNormals<3>(const Points<3>&, Points<3>&, const NormalEstimationOptions&);
template double orientationDisagreement<2>(const Points<2>&, const Points<2>&, const NormalEstimationOptions&);
template double orientationDisagreement<3>(const Points<3>&, const Points<3>&, const NormalEstimationOptions&);
template int orientNormalLines<2>(const Points<2>&, Points<2>&, const NormalEstimationOptions&);
template int orientNormalLines<3>(const Points<3>&, Points<3>&, const NormalEstimationOptions&);

}  // namespace hermite
