#include "core/points/sheet_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <Eigen/Eigenvalues>

namespace hermite::detail {

namespace {

// The smallest-eigenvalue eigenvector of a covariance, unit (UnitX when it is not finite).
template <int Dim>
Vec<Dim> smallestEigenvector(const Mat<Dim>& C) {
  Eigen::SelfAdjointEigenSolver<Mat<Dim>> eig(C);
  Vec<Dim> nrm = eig.eigenvectors().col(0);  // smallest eigenvalue first
  if (!(nrm.norm() > 0) || !nrm.allFinite()) nrm = Vec<Dim>::UnitX();
  return nrm.normalized();
}

// The unit eigenvector of the smallest eigenvalue of the covariance of the points `idx`.
template <int Dim>
Vec<Dim> pcaNormal(const Points<Dim>& points, const std::uint32_t* idx, int count) {
  Vec<Dim> mean = Vec<Dim>::Zero();
  for (int j = 0; j < count; ++j) mean += points.col(idx[j]);
  mean /= count;
  Mat<Dim> C = Mat<Dim>::Zero();
  for (int j = 0; j < count; ++j) {
    const Vec<Dim> d = points.col(idx[j]) - mean;
    C += d * d.transpose();
  }
  return smallestEigenvector<Dim>(C);
}

// The normal of the hyperplane through Dim points `q` (columns), or zero when they span none.
template <int Dim>
Vec<Dim> spanNormal(const Mat<Dim>& q) {
  if constexpr (Dim == 2) {
    const Vec<2> a = q.col(1) - q.col(0);
    return Vec<2>(-a.y(), a.x());
  } else {
    return (q.col(1) - q.col(0)).cross(q.col(2) - q.col(0));
  }
}

// A local model of the k neighbourhood of pᵢ (offsets h = n·(pⱼ − pᵢ)): the sheet through pᵢ,
// and, when `twoSheets`, a parallel sheet at offset `second`.
template <int Dim>
struct SheetModel {
  Vec<Dim> normal = Vec<Dim>::UnitX();
  double second = 0;
  bool twoSheets = false;
  double score = std::numeric_limits<double>::infinity();
};

// The best one-sheet and two-sheet models of a neighbourhood (Q: Dim × k, the neighbours minus
// pᵢ) over the candidate normals of the hyperplanes through Dim of its points (sheetNormal).
template <int Dim>
std::pair<SheetModel<Dim>, SheetModel<Dim>> fitSheets(const Eigen::Matrix<double, Dim, Eigen::Dynamic>& Q, double band) {
  const int k = static_cast<int>(Q.cols());
  const double band2 = band * band;
  SheetModel<Dim> one, two;
  auto consider = [&](Vec<Dim> nrm) {
    const double len = nrm.norm();
    if (!(len > 1e-12 * band2)) return;
    nrm /= len;
    // One sheet through pᵢ; the second at the mean offset of the outliers on the side with more.
    double s1 = 0, up = 0, down = 0;
    int nUp = 0, nDown = 0;
    for (int j = 0; j < k; ++j) {
      const double h = nrm.dot(Q.col(j));
      s1 += std::min(band2, h * h);
      if (h > band) up += h, ++nUp;
      if (h < -band) down += h, ++nDown;
    }
    if (s1 < one.score) one = {nrm, 0, false, s1};
    if (std::max(nUp, nDown) < 2) return;
    const double c = nUp >= nDown ? up / nUp : down / nDown;
    double s2 = 0;
    for (int j = 0; j < k; ++j) {
      const double h = nrm.dot(Q.col(j));
      s2 += std::min(band2, std::min(h * h, (h - c) * (h - c)));
    }
    if (s2 < two.score) two = {nrm, c, true, s2};
  };
  Mat<Dim> q;
  if constexpr (Dim == 2) {
    for (int a = 0; a < k; ++a)
      for (int b = a + 1; b < k; ++b) {
        q << Q.col(a), Q.col(b);
        consider(spanNormal<Dim>(q));
      }
  } else {
    for (int a = 0; a < k; ++a)
      for (int b = a + 1; b < k; ++b)
        for (int c = b + 1; c < k; ++c) {
          q << Q.col(a), Q.col(b), Q.col(c);
          consider(spanNormal<Dim>(q));
        }
  }
  return {one, two};
}

// The normal of model m refitted to its inliers (|h| ≤ band on pᵢ's sheet, |h − c| ≤ band on the
// second), each sheet about its own mean; `second` receives c times it. `fallback` when fewer
// than Dim + 1 fit.
template <int Dim>
Vec<Dim> refitSheets(const Eigen::Matrix<double, Dim, Eigen::Dynamic>& Q, const SheetModel<Dim>& m, double band,
                     const Vec<Dim>& fallback, Vec<Dim>& second) {
  Vec<Dim> sum[2] = {Vec<Dim>::Zero(), Vec<Dim>::Zero()};
  Mat<Dim> outer = Mat<Dim>::Zero();
  int count[2] = {0, 0};
  for (Eigen::Index j = 0; j < Q.cols(); ++j) {
    const double h = m.normal.dot(Q.col(j));
    const int sheet = std::abs(h) <= band ? 0 : m.twoSheets && std::abs(h - m.second) <= band ? 1 : -1;
    if (sheet < 0) continue;
    sum[sheet] += Q.col(j);
    outer += Q.col(j) * Q.col(j).transpose();
    ++count[sheet];
  }
  if (count[0] + count[1] < Dim + 1) return fallback;
  Mat<Dim> C = outer;
  for (int sh = 0; sh < 2; ++sh)
    if (count[sh] > 0) C -= sum[sh] * sum[sh].transpose() / count[sh];
  const Vec<Dim> nrm = smallestEigenvector<Dim>(C);
  if (m.twoSheets && count[1] > 0) second = nrm * nrm.dot(sum[1] / count[1]);
  return nrm;
}

}  // namespace

template <int Dim>
std::vector<double> sheetBands(const Points<Dim>& points, const NeighbourGraph& g, double sheetBand) {
  const int n = static_cast<int>(points.cols());
  std::vector<double> band(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    double radius = 0;
    for (int j = 0; j < g.k; ++j) radius = std::max(radius, (points.col(g.of(i)[j]) - points.col(i)).norm());
    band[i] = sheetBand * radius;
  }
  return band;
}

template <int Dim>
Vec<Dim> sheetNormal(const Points<Dim>& points, const NeighbourGraph& g, int i, double band, Vec<Dim>& second) {
  const std::uint32_t* idx = g.of(i);
  Eigen::Matrix<double, Dim, Eigen::Dynamic> Q(Dim, g.k);
  for (int j = 0; j < g.k; ++j) Q.col(j) = points.col(idx[j]) - points.col(i);
  second = Vec<Dim>::Zero();
  // One sheet (most points): PCA's hyperplane through pᵢ holds all k within band / 2. In 2D also
  // when the line through their mean holds them within 0.75·band: the k samples of a curve span
  // k spacings of arc (a 3D neighbourhood is a disc ~1.8 spacings across), so curvature, not a
  // second sheet, moves its ends off the tangent (10 of 40 samples on a circle: ±0.15·r).
  const Vec<Dim> pca = pcaNormal<Dim>(points, idx, g.k);
  const Eigen::Matrix<double, 1, Eigen::Dynamic> off = pca.transpose() * Q;
  if (off.cwiseAbs().maxCoeff() <= 0.5 * band) return pca;
  if (Dim == 2 && (off.array() - off.mean()).abs().maxCoeff() <= 0.75 * band) return pca;
  const auto [one, two] = fitSheets<Dim>(Q, band);
  return refitSheets<Dim>(Q, two.score <= one.score - 2 * band * band ? two : one, band, pca, second);
}

template std::vector<double> sheetBands<2>(const Points<2>&, const NeighbourGraph&, double);
template std::vector<double> sheetBands<3>(const Points<3>&, const NeighbourGraph&, double);
template Vec<2> sheetNormal<2>(const Points<2>&, const NeighbourGraph&, int, double, Vec<2>&);
template Vec<3> sheetNormal<3>(const Points<3>&, const NeighbourGraph&, int, double, Vec<3>&);

}  // namespace hermite::detail
