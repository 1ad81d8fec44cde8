// Minimum-weight triangulation of a hole's boundary polygon (min_weight_triangulation.h).

#include "core/mesh/min_weight_triangulation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "core/base/geometry.h"
#include "core/mesh/patch_refinement.h"
#include "core/mesh/near_mesh_distance.h"

namespace hermite {

namespace {

constexpr double kBadAngle = std::numbers::pi / 180.0;  // 1°: smaller angles make a bad triangle

// The weight of a (partial) triangulation, compared lexicographically.
struct Weight {
  int bad = 0;            // triangles with an angle below 1°
  double dihedral = 0;    // largest angle between neighbouring triangles' normals, radians
  double area = 0;        // total
  bool operator<(const Weight& o) const {
    if (bad != o.bad) return bad < o.bad;
    if (dihedral != o.dihedral) return dihedral < o.dihedral;
    return area < o.area;
  }
  Weight operator+(const Weight& o) const { return {bad + o.bad, std::max(dihedral, o.dihedral), area + o.area}; }
};

const Weight kInfinite{std::numeric_limits<int>::max() / 4, 0, 0};

double angleBetween(const Vec<3>& a, const Vec<3>& b) {
  const double na = a.norm(), nb = b.norm();
  if (na == 0 || nb == 0) return std::numbers::pi;
  return std::acos(std::clamp(a.dot(b) / (na * nb), -1.0, 1.0));
}

double smallestAngle(const Vec<3>& a, const Vec<3>& b, const Vec<3>& c) {
  return std::min({angleBetween(b - a, c - a), angleBetween(a - b, c - b), angleBetween(a - c, b - c)});
}

// One polygon to triangulate: positions in loop order, the outward normal of the triangle across
// each edge (i, i+1) — the last edge closes the polygon — or zero when there is none (a chord),
// and which vertex pairs may not become edges (they are edges of the mesh already).
struct Polygon {
  std::vector<Vec<3>> points;
  std::vector<Vec<3>> edgeNormals;
  std::vector<int> ids;  // mesh vertex ids
};

class Triangulator {
 public:
  Triangulator(const Polygon& polygon, const std::unordered_set<std::uint64_t>& meshEdges)
      : p_(polygon), meshEdges_(meshEdges), n_(int(polygon.points.size())),
        weight_(std::size_t(n_) * n_, Weight{}), split_(std::size_t(n_) * n_, -1) {}

  // Appends the triangles (mesh ids, reversed loop order: the orientation of the mesh across
  // the boundary) to `out` and raises maxDihedral to theirs; false when no triangulation avoids
  // the mesh's own edges.
  bool run(std::vector<Eigen::Vector3i>& out, double& maxDihedral) {
    for (int gap = 2; gap < n_; ++gap)
      for (int i = 0; i + gap < n_; ++i) solve(i, i + gap);
    if (split_[index(0, n_ - 1)] < 0) return false;
    maxDihedral = std::max(maxDihedral, weight_[index(0, n_ - 1)].dihedral);
    emit(0, n_ - 1, out);
    return true;
  }

 private:
  std::size_t index(int i, int j) const { return std::size_t(i) * n_ + j; }

  // Normal of the triangle on the far side of edge (i, j), i < j: the mesh's along the boundary,
  // the chosen sub-triangulation's inside, zero across a chord.
  Vec<3> farNormal(int i, int j) const {
    if (j == i + 1) return p_.edgeNormals[i];
    if (i == 0 && j == n_ - 1) return p_.edgeNormals[n_ - 1];
    const int k = split_[index(i, j)];
    return triangleNormal(i, k, j);
  }

  Vec<3> triangleNormal(int i, int k, int j) const {
    return (p_.points[i] - p_.points[k]).cross(p_.points[j] - p_.points[k]);
  }

  bool allowedEdge(int i, int j) const {
    if (j == i + 1 || (i == 0 && j == n_ - 1)) return true;
    return !meshEdges_.count(edgeKey(p_.ids[i], p_.ids[j]));
  }

  void solve(int i, int j) {
    if (!allowedEdge(i, j)) {
      weight_[index(i, j)] = kInfinite;
      return;
    }
    Weight best = kInfinite;
    int bestK = -1;
    for (int k = i + 1; k < j; ++k) {
      const Weight& left = weight_[index(i, k)];
      const Weight& right = weight_[index(k, j)];
      if (left.bad >= kInfinite.bad || right.bad >= kInfinite.bad) continue;
      const Vec<3> normal = triangleNormal(i, k, j);
      Weight w = left + right;
      w.area += 0.5 * normal.norm();
      w.bad += smallestAngle(p_.points[i], p_.points[k], p_.points[j]) < kBadAngle;
      for (const Vec<3>& other : {farNormal(i, k), farNormal(k, j)})
        if (other.squaredNorm() > 0) w.dihedral = std::max(w.dihedral, angleBetween(normal, other));
      if (i == 0 && j == n_ - 1 && p_.edgeNormals[n_ - 1].squaredNorm() > 0)
        w.dihedral = std::max(w.dihedral, angleBetween(normal, p_.edgeNormals[n_ - 1]));
      if (bestK < 0 || w < best) best = w, bestK = k;
    }
    weight_[index(i, j)] = best;
    split_[index(i, j)] = bestK;
  }

  void emit(int i, int j, std::vector<Eigen::Vector3i>& out) const {
    if (j - i < 2) return;
    const int k = split_[index(i, j)];
    out.emplace_back(p_.ids[k], p_.ids[i], p_.ids[j]);
    emit(i, k, out);
    emit(k, j, out);
  }

  const Polygon& p_;
  const std::unordered_set<std::uint64_t>& meshEdges_;
  int n_;
  std::vector<Weight> weight_;  // best weight of the sub-polygon i … j
  std::vector<int> split_;      // its apex k, or −1
};

// Thrown when the caller's keepGoing says stop; minWeightTriangulation returns no triangles.
struct TriangulationStopped {};

// The chord (i, j) that best cuts a polygon of n > maxDirect vertices: both parts keep at least
// n/4 vertices, the chord is not a mesh edge, and it is the shortest relative to the shorter of
// the two boundary paths it bridges.
std::pair<int, int> bestChord(const Polygon& p, const std::unordered_set<std::uint64_t>& meshEdges,
                              const std::function<bool()>& keepGoing) {
  const int n = int(p.points.size());
  std::vector<double> arc(std::size_t(n) + 1, 0.0);  // boundary length from vertex 0
  for (int i = 0; i < n; ++i) arc[i + 1] = arc[i] + (p.points[(i + 1) % n] - p.points[i]).norm();
  const int minPart = std::max(3, n / 4);
  double best = std::numeric_limits<double>::infinity();
  std::pair<int, int> chord{0, n / 2};
  for (int i = 0; i < n; ++i) {
    if (i % 64 == 0 && keepGoing && !keepGoing()) throw TriangulationStopped{};
    for (int j = i + minPart; j <= i + n - minPart && j < n; ++j) {
      if (meshEdges.count(edgeKey(p.ids[i], p.ids[j]))) continue;
      const double path = std::min(arc[j] - arc[i], arc[n] - (arc[j] - arc[i]));
      const double ratio = (p.points[j] - p.points[i]).norm() / std::max(path, 1e-300);
      if (ratio < best) best = ratio, chord = {i, j};
    }
  }
  return chord;
}

// The part of polygon p from vertex a to vertex b (cyclically, inclusive); its closing edge
// (b, a) is the chord, with no neighbour normal.
Polygon subPolygon(const Polygon& p, int a, int b) {
  const int n = int(p.points.size());
  Polygon out;
  for (int i = a;; i = (i + 1) % n) {
    out.points.push_back(p.points[i]);
    out.ids.push_back(p.ids[i]);
    out.edgeNormals.push_back(i == b ? Vec<3>::Zero() : p.edgeNormals[i]);
    if (i == b) break;
  }
  return out;
}

bool triangulate(const Polygon& p, const std::unordered_set<std::uint64_t>& meshEdges, int maxDirect,
                 std::vector<Eigen::Vector3i>& out, double& maxDihedral, const std::function<bool()>& keepGoing) {
  if (int(p.points.size()) <= maxDirect) {
    if (keepGoing && !keepGoing()) throw TriangulationStopped{};
    return Triangulator(p, meshEdges).run(out, maxDihedral);
  }
  const auto [i, j] = bestChord(p, meshEdges, keepGoing);
  return triangulate(subPolygon(p, i, j), meshEdges, maxDirect, out, maxDihedral, keepGoing) &&
         triangulate(subPolygon(p, j, i), meshEdges, maxDirect, out, maxDihedral, keepGoing);
}

// The outward normal of the mesh triangle holding directed edge a → b (zero if none).
Vec<3> meshNormalAcross(const PreparedMesh& prepared, int a, int b) {
  const TriMesh& mesh = prepared.mesh();
  for (const int* t = prepared.trianglesBegin(a); t != prepared.trianglesEnd(a); ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles(k, *t) == a && mesh.triangles((k + 1) % 3, *t) == b) {
        const Vec<3> p0 = mesh.vertices.col(mesh.triangles(0, *t)), p1 = mesh.vertices.col(mesh.triangles(1, *t)),
                     p2 = mesh.vertices.col(mesh.triangles(2, *t));
        return (p1 - p0).cross(p2 - p0);
      }
  return Vec<3>::Zero();
}

// x as a percentage with one decimal: 0.0123 → "1.2 %".
std::string percent(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f %%", 100.0 * x);
  return text;
}

// The diameter of the loop: the largest distance between two of its vertices.
double loopDiameter(const Eigen::Matrix3Xd& V, const BoundaryLoop& loop) {
  double diameter = 0;
  for (std::size_t i = 0; i < loop.size(); ++i)
    for (std::size_t j = i + 1; j < loop.size(); ++j) diameter = std::max(diameter, (V.col(loop[j]) - V.col(loop[i])).norm());
  return diameter;
}

// The 90th percentile over `triangles` of the distance from each one's centroid to the mesh's
// triangles, capped at `cap`: near zero when the triangulation lies on the mesh itself (the rim
// of an open sheet filled by a second copy of the sheet). A triangulation without inner vertices
// has most of its triangles along the rim, where even a real wedge is thin, hence a high
// percentile rather than the median.
double gapPercentileToMesh(const TriMesh& mesh, const Eigen::Matrix3Xi& triangles, double cap) {
  if (triangles.cols() == 0) return 0;
  const Eigen::Matrix3Xd& V = mesh.vertices;
  Points<3> centroids(3, triangles.cols());
  for (Eigen::Index t = 0; t < triangles.cols(); ++t)
    centroids.col(t) = (V.col(triangles(0, t)) + V.col(triangles(1, t)) + V.col(triangles(2, t))) / 3.0;
  std::vector<double> gaps = distancesToMeshWithin(mesh, centroids, cap);
  const std::size_t k = gaps.size() * 9 / 10;
  std::nth_element(gaps.begin(), gaps.begin() + std::ptrdiff_t(k), gaps.end());
  return gaps[k];
}

}  // namespace

Eigen::Matrix3Xi minWeightTriangulation(const PreparedMesh& prepared, const BoundaryLoop& loop, int maxDirect,
                                        double* maxDihedral, const std::function<bool()>& keepGoing) {
  const int n = int(loop.size());
  Polygon polygon;
  std::unordered_set<int> onLoop(loop.begin(), loop.end());
  std::unordered_set<std::uint64_t> meshEdges;  // mesh edges between two loop vertices
  for (int i = 0; i < n; ++i) {
    polygon.points.push_back(prepared.mesh().vertices.col(loop[i]));
    polygon.ids.push_back(loop[i]);
    polygon.edgeNormals.push_back(meshNormalAcross(prepared, loop[i], loop[(i + 1) % n]));
    for (int v : prepared.neighbours(loop[i]))
      if (onLoop.count(v)) meshEdges.insert(edgeKey(loop[i], v));
  }
  std::vector<Eigen::Vector3i> triangles;
  double dihedral = 0;
  bool ok = false;
  try {
    ok = n >= 3 && triangulate(polygon, meshEdges, std::max(maxDirect, 8), triangles, dihedral, keepGoing);
  } catch (const TriangulationStopped&) {
    ok = false;
  }
  if (maxDihedral) *maxDihedral = dihedral;
  if (!ok) return Eigen::Matrix3Xi(3, 0);
  Eigen::Matrix3Xi out(3, Eigen::Index(triangles.size()));
  for (std::size_t t = 0; t < triangles.size(); ++t) out.col(Eigen::Index(t)) = triangles[t];
  return out;
}

double medianBoundaryDihedral(const PreparedMesh& prepared, const BoundaryLoop& loop, const Eigen::Matrix3Xi& triangles) {
  const Eigen::Matrix3Xd& V = prepared.mesh().vertices;
  std::unordered_map<std::uint64_t, Vec<3>> patchNormal;  // directed edge b → a of a patch triangle
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    const Vec<3> n = (V.col(triangles(1, t)) - V.col(triangles(0, t))).cross(V.col(triangles(2, t)) - V.col(triangles(0, t)));
    for (int c = 0; c < 3; ++c)
      patchNormal[(std::uint64_t(std::uint32_t(triangles(c, t))) << 32) | std::uint32_t(triangles((c + 1) % 3, t))] = n;
  }
  std::vector<double> angles;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const int a = loop[i], b = loop[(i + 1) % loop.size()];
    const auto it = patchNormal.find((std::uint64_t(std::uint32_t(b)) << 32) | std::uint32_t(a));
    const Vec<3> mesh = meshNormalAcross(prepared, a, b);
    angles.push_back(it == patchNormal.end() || mesh.squaredNorm() == 0 ? std::numbers::pi : angleBetween(mesh, it->second));
  }
  if (angles.empty()) return std::numbers::pi;
  std::nth_element(angles.begin(), angles.begin() + angles.size() / 2, angles.end());
  return angles[angles.size() / 2];
}

HolePatch minWeightPatch(const PreparedMesh& prepared, const BoundaryLoop& loop,
                         const std::function<bool(double)>& progress) {
  HolePatch patch;
  patch.loop = loop;
  patch.baseId = prepared.mesh().vertexCount();
  patch.vertices.resize(3, 0);
  patch.vertexNormals.resize(3, 0);
  bool stopped = false;
  const Eigen::Matrix3Xi triangles = minWeightTriangulation(prepared, loop, 96, nullptr, [&] {
    stopped = stopped || (progress && !progress(0.0));
    return !stopped;
  });
  patch.triangles.resize(3, 0);
  if (stopped) {
    patch.failure = "cancelled";
    return patch;
  }
  if (triangles.cols() == 0) {
    patch.failure = "no triangulation of the boundary avoids the mesh's own edges (the hole touches itself)";
    return patch;
  }
  const Eigen::Matrix3Xd& V = prepared.mesh().vertices;
  patch.diameter = loopDiameter(V, loop);
  // A sharp fold at the rim is a thin wedge (a blade's missing face) unless the triangulation
  // lies on the mesh itself: then the loop is the rim of an open sheet.
  if (const double dihedral = medianBoundaryDihedral(prepared, loop, triangles); dihedral > kRimDihedral) {
    const double gap = gapPercentileToMesh(prepared.mesh(), triangles, kSheetGap * patch.diameter);
    if (gap < kSheetGap * patch.diameter) {
      patch.failure = "every triangulation folds back onto the mesh (" + std::to_string(int(dihedral * 180 / M_PI)) +
                      "° between neighbours) and lies on it (90 % of its triangles within " + percent(gap / patch.diameter) +
                      " of the hole's width): the rim of an open surface, not a hole";
      return patch;
    }
    patch.rimFold = dihedral;
  }
  patch.triangles = triangles;
  double length = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) length += (V.col(loop[(i + 1) % loop.size()]) - V.col(loop[i])).norm();
  patch.meanEdgeLength = length / double(loop.size());
  double area = 0;
  for (Eigen::Index t = 0; t < triangles.cols(); ++t)
    area += 0.5 * (V.col(triangles(1, t)) - V.col(triangles(0, t))).cross(V.col(triangles(2, t)) - V.col(triangles(0, t))).norm();
  const double uniformCount = area / (std::sqrt(3.0) / 4.0 * patch.meanEdgeLength * patch.meanEdgeLength);
  const double grading = uniformCount > kUniformPatchTriangles ? kPatchGrading : 0.0;
  patch.graded = grading > 0;
  if (!refinePatch(prepared, patch, progress, grading)) {
    patch.failure = "cancelled";
    return patch;
  }
  patch.closed = true;
  return patch;
}

}  // namespace hermite
