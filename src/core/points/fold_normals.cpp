#include "core/points/fold_normals.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <Eigen/Eigenvalues>

namespace hermite::detail {

namespace {

constexpr double kCos30 = 0.8660254037844386;
constexpr double kEndFraction = 0.2;  // × the radius: the sheets' centroid this far aside, i is at their end

// A view of some columns of a Dim × N matrix (the ring's buffers: no copy, no allocation).
template <int Dim>
using ColumnsRef = Eigen::Ref<const Points<Dim>>;

// The two opposite-facing sheets of a neighbourhood (foldNormals, step 1), relative to pᵢ.
template <int Dim>
struct SheetPair {
  Vec<Dim> axis;             // e, unit
  Vec<Dim> normal[2];        // mean unit normal of sheet "−" and sheet "+"
  double offset[2] = {0, 0};  // h₋, h₊: median offset along e of each sheet from pᵢ
  Vec<Dim> centroid;         // of both sheets' points, minus pᵢ
};

// Whether pᵢ's neighbourhood may hold two opposite-facing sheets, or pᵢ's normal disagrees with
// its neighbours' (a cheap test on the k − 1 unit normals `m` of the neighbours that skips every
// point of a consistently oriented single sheet): two of them more than 150° apart, or `own`
// within 30° of fewer than half of them.
template <int Dim>
bool worthALook(const ColumnsRef<Dim>& m, const Vec<Dim>& own) {
  int agree = 0;
  for (Eigen::Index a = 0; a < m.cols(); ++a) {
    agree += m.col(a).dot(own) >= kCos30;
    for (Eigen::Index b = a + 1; b < m.cols(); ++b)
      if (m.col(a).dot(m.col(b)) < -kCos30) return true;
  }
  return 2 * agree < m.cols();
}

// The main axis (unit) of the lines `m` whose columns `use` selects: the largest eigenvector of Σ mⱼ mⱼᵀ.
template <int Dim>
Vec<Dim> mainAxis(const ColumnsRef<Dim>& m, const std::vector<char>& use) {
  Mat<Dim> C = Mat<Dim>::Zero();
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    if (use[static_cast<std::size_t>(j)]) C += m.col(j) * m.col(j).transpose();
  Eigen::SelfAdjointEigenSolver<Mat<Dim>> eig;
  eig.computeDirect(C);  // closed form: the axis of a neighbourhood needs no more precision
  return eig.eigenvectors().col(Dim - 1);  // largest eigenvalue last
}

// The median of `h` (not empty; reordered).
double median(std::vector<double>& h) {
  const auto mid = h.begin() + static_cast<std::ptrdiff_t>(h.size() / 2);
  std::nth_element(h.begin(), mid, h.end());
  return *mid;
}

// The sheets' axis among the lines `m` (unit columns): their main axis, refitted once to the
// lines within 30° of it (the rim's own lines and bad lines out); `use` receives which lines lie
// within 30° of the result.
template <int Dim>
Vec<Dim> sheetAxis(const ColumnsRef<Dim>& m, std::vector<char>& use) {
  const std::size_t count = static_cast<std::size_t>(m.cols());
  use.assign(count, 1);
  Vec<Dim> axis = mainAxis<Dim>(m, use);
  for (int pass = 0; pass < 2; ++pass) {
    int along = 0;
    for (std::size_t j = 0; j < count; ++j)
      along += use[j] = std::abs(m.col(static_cast<Eigen::Index>(j)).dot(axis)) >= kCos30;
    if (pass == 0 && along >= Dim + 1) axis = mainAxis<Dim>(m, use);
  }
  return axis;
}

// Step 1 of foldNormals over the ring of points around pᵢ (`m`: their unit normals, `d`: their
// positions minus pᵢ): the two sheets, or false when there are not two of at least 3 points
// each, `band` or more apart. The offsets are medians (a sign error stays out).
template <int Dim>
bool sheetPair(const ColumnsRef<Dim>& m, const ColumnsRef<Dim>& d, double band, SheetPair<Dim>& s) {
  const std::size_t count = static_cast<std::size_t>(m.cols());
  std::vector<char> use;
  s.axis = sheetAxis<Dim>(m, use);
  if (!s.axis.allFinite()) return false;
  Vec<Dim> sum[2] = {Vec<Dim>::Zero(), Vec<Dim>::Zero()}, at = Vec<Dim>::Zero();
  std::vector<double> h[2];
  for (std::size_t j = 0; j < count; ++j) {
    const Eigen::Index c = static_cast<Eigen::Index>(j);
    const double cosine = m.col(c).dot(s.axis);
    if (std::abs(cosine) < kCos30) continue;
    const int side = cosine > 0 ? 1 : 0;
    sum[side] += m.col(c);
    at += d.col(c);
    h[side].push_back(s.axis.dot(d.col(c)));
  }
  if (h[0].size() < 3 || h[1].size() < 3) return false;
  for (int side = 0; side < 2; ++side) {
    s.normal[side] = sum[side].normalized();
    s.offset[side] = median(h[side]);
  }
  s.centroid = at / double(h[0].size() + h[1].size());
  return std::abs(s.offset[1] - s.offset[0]) >= band && s.offset[1] != s.offset[0];
}

// Steps 2–4 of foldNormals: pᵢ's normal from the sheet pair (`own`: its oriented estimate,
// `radius`: its neighbourhood radius).
template <int Dim>
Vec<Dim> foldNormal(const SheetPair<Dim>& s, const Vec<Dim>& own, double radius) {
  const double sep = s.offset[1] - s.offset[0];
  const double f = std::clamp(-s.offset[0] / sep, 0.0, 1.0);
  const Vec<Dim>& near = s.normal[f > 0.5 ? 1 : 0];
  const Vec<Dim> sheet = own.dot(near) >= kCos30 ? own : near;
  const Vec<Dim> aside = s.centroid - s.axis * s.axis.dot(s.centroid);  // ⊥ e
  const double w = std::clamp((std::min(f, 1 - f) - 0.05) / 0.2, 0.0, 1.0);
  if (w == 0 || aside.norm() < kEndFraction * radius) return sheet;
  const Vec<Dim> fold = aside.normalized() * (sep > 0 ? -1.0 : 1.0);  // convex: away from the sheets
  return (w * fold + (1 - w) * sheet).normalized();
}

// Whether pᵢ lies on a sheet of its own: at least 3 of its k neighbours lie within a tenth of a
// band of its tangent plane (`own`: its oriented unit normal) with normals within 30° of it.
// Then pᵢ lies at a sheet's level of any pair of sheets around it (f ≈ 0: not between them, no
// fold direction to blend in) and agrees with that sheet's normal: the ring need not be looked
// at. Most samples of a thin part pass, the rims' do not.
template <int Dim>
bool onItsSheet(const Points<Dim>& P, const Points<Dim>& N, const NeighbourGraph& g, int i, const Vec<Dim>& own,
                double band) {
  int level = 0;
  for (int j = 0; j < g.k; ++j) {
    const int o = static_cast<int>(g.of(i)[j]);
    if (o == i || std::abs(own.dot(P.col(o) - P.col(i))) > 0.1 * band) continue;
    level += own.dot(N.col(o).normalized()) >= kCos30;
  }
  return level >= 3;
}

// The ring around pᵢ: its neighbours and theirs (pᵢ excluded), about three neighbourhoods' worth
// of points: enough sheet points beyond a rim's cluster of bad lines to say where the sheets are.
void ringOf(const NeighbourGraph& g, int i, std::vector<std::uint32_t>& ring, std::vector<int>& stamp) {
  ring.clear();
  stamp[static_cast<std::size_t>(i)] = i;  // `stamp` (N entries) marks the points listed for i
  for (int a = 0; a < g.k; ++a)
    for (int b = 0; b < g.k; ++b) {
      const std::uint32_t o = g.of(static_cast<int>(g.of(i)[a]))[b];
      if (stamp[o] != i) stamp[o] = i, ring.push_back(o);
    }
}

// Whether pᵢ lies between two sheets of its ring, from lines alone (betweenSheets): the offsets
// e·(pⱼ − pᵢ) of the ring's lines along the sheets' axis e, split at their widest gap into two
// levels of at least 3 each, their medians at least `band` apart, pᵢ 15 % or more of the way
// from each (curvature lifts a sheet's own ring to one side, by ≈ 7 % at a spacing from a curl of
// radius 20 spacings).
template <int Dim>
bool liesBetween(const ColumnsRef<Dim>& m, const ColumnsRef<Dim>& d, double band) {
  std::vector<char> use;
  const Vec<Dim> axis = sheetAxis<Dim>(m, use);
  std::vector<double> h;
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    if (use[static_cast<std::size_t>(j)]) h.push_back(axis.dot(d.col(j)));
  if (h.size() < 6 || !axis.allFinite()) return false;
  std::sort(h.begin(), h.end());
  std::size_t cut = 0;
  double widest = 0;
  for (std::size_t a = 3; a + 3 <= h.size(); ++a)
    if (h[a] - h[a - 1] > widest) widest = h[a] - h[a - 1], cut = a;
  if (cut == 0) return false;
  const double lo = h[(cut - 1) / 2], hi = h[cut + (h.size() - cut - 1) / 2];
  if (hi - lo < band) return false;
  const double f = -lo / (hi - lo);
  return f >= 0.15 && f <= 0.85;
}

// The unit normals (the first columns of `m`) and offsets from pᵢ (of `d`) of the points `ring`;
// the buffers grow to the largest ring (k² columns at most). Returns the count.
template <int Dim>
Eigen::Index gather(const Points<Dim>& P, const Points<Dim>& N, int i, const std::vector<std::uint32_t>& ring,
                    Points<Dim>& m, Points<Dim>& d) {
  const Eigen::Index count = static_cast<Eigen::Index>(ring.size());
  if (m.cols() < count) m.resize(Dim, count), d.resize(Dim, count);
  for (Eigen::Index j = 0; j < count; ++j) {
    m.col(j) = N.col(ring[static_cast<std::size_t>(j)]).normalized();
    d.col(j) = P.col(ring[static_cast<std::size_t>(j)]) - P.col(i);
  }
  return count;
}

}  // namespace

template <int Dim>
std::vector<char> betweenSheets(const Points<Dim>& P, const Points<Dim>& N, const NeighbourGraph& g,
                                const std::vector<double>& band) {
  const int n = static_cast<int>(P.cols());
  std::vector<char> between(static_cast<std::size_t>(n), 0);
#pragma omp parallel
  {
    Points<Dim> m, d;
    std::vector<std::uint32_t> ring;
    std::vector<int> stamp(static_cast<std::size_t>(n), -1);
#pragma omp for schedule(dynamic, 1024)
    for (int i = 0; i < n; ++i) {
      // Cheap test first: the k neighbours' offsets along pᵢ's line span a band or more (a rim
      // sample whose line is not the sheets' is no bridge between them: no edge along a sheet).
      const Vec<Dim> own = N.col(i).normalized();
      double lo = 0, hi = 0;
      for (int j = 0; j < g.k; ++j) {
        const double h = own.dot(P.col(g.of(i)[j]) - P.col(i));
        lo = std::min(lo, h), hi = std::max(hi, h);
      }
      if (!(hi - lo >= band[i])) continue;
      ringOf(g, i, ring, stamp);
      const Eigen::Index count = gather<Dim>(P, N, i, ring, m, d);
      between[static_cast<std::size_t>(i)] = liesBetween<Dim>(m.leftCols(count), d.leftCols(count), band[i]);
    }
  }
  return between;
}

template <int Dim>
int foldNormals(const Points<Dim>& P, Points<Dim>& N, const std::vector<char>& fixed, const NeighbourGraph& g,
                const std::vector<double>& band, double sheetBand) {
  const int n = static_cast<int>(P.cols());
  Points<Dim> out = N;
  int changed = 0;
#pragma omp parallel reduction(+ : changed)
  {
    Points<Dim> m(Dim, g.k), rm, d;
    std::vector<std::uint32_t> ring;
    std::vector<int> stamp(static_cast<std::size_t>(n), -1);
#pragma omp for schedule(dynamic, 1024)
    for (int i = 0; i < n; ++i) {
      if (fixed[i]) continue;
      const Vec<Dim> own = N.col(i).normalized();
      Eigen::Index c = 0;
      for (int j = 0; j < g.k; ++j)
        if (static_cast<int>(g.of(i)[j]) != i) m.col(c++) = N.col(g.of(i)[j]).normalized();
      if (!worthALook<Dim>(m.leftCols(c), own) || onItsSheet<Dim>(P, N, g, i, own, band[i])) continue;
      ringOf(g, i, ring, stamp);
      const Eigen::Index count = gather<Dim>(P, N, i, ring, rm, d);
      SheetPair<Dim> s;
      if (!sheetPair<Dim>(rm.leftCols(count), d.leftCols(count), band[i], s)) continue;
      const Vec<Dim> nrm = foldNormal<Dim>(s, own, band[i] / sheetBand);
      if (nrm.allFinite() && nrm != own) out.col(i) = nrm, ++changed;
    }
  }
  N = out;
  return changed;
}

template std::vector<char> betweenSheets<2>(const Points<2>&, const Points<2>&, const NeighbourGraph&,
                                            const std::vector<double>&);
template std::vector<char> betweenSheets<3>(const Points<3>&, const Points<3>&, const NeighbourGraph&,
                                            const std::vector<double>&);
template int foldNormals<2>(const Points<2>&, Points<2>&, const std::vector<char>&, const NeighbourGraph&,
                            const std::vector<double>&, double);
template int foldNormals<3>(const Points<3>&, Points<3>&, const std::vector<char>&, const NeighbourGraph&,
                            const std::vector<double>&, double);

}  // namespace hermite::detail
