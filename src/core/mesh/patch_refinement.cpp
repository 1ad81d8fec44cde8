// Longest-edge splitting and angle-improving flips of a hole patch (patch_refinement.h).

#include "core/mesh/patch_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <unordered_set>

#include "core/base/geometry.h"

namespace hermite {

namespace {

// cos of the angle at `at` (1 for a degenerate corner): larger means sharper.
double cornerCosine(const Vec<3>& at, const Vec<3>& b, const Vec<3>& c) {
  const Vec<3> u = b - at, v = c - at;
  const double nu = u.norm(), nv = v.norm();
  if (nu == 0 || nv == 0) return 1;
  return u.dot(v) / (nu * nv);
}

// The patch as an editable triangle set with edge → triangle adjacency; vertex ids are the
// mesh's (< baseId) and the patch's (≥ baseId).
class EditablePatch {
 public:
  // `grading` ≥ 0: the target edge length at a vertex is meanEdgeLength + grading × its distance
  // to the nearest boundary vertex (0: uniform).
  EditablePatch(const PreparedMesh& prepared, HolePatch& patch, double grading = 0)
      : prepared_(prepared), patch_(patch), grading_(grading) {
    const std::size_t n = patch.loop.size();
    for (std::size_t i = 0; i < n; ++i) {
      const Vec<3> p = prepared.mesh().vertices.col(patch.loop[i]);
      boundaryPoints_.push_back(p);
      boundaryScale_[patch.loop[i]] = 0.5 * ((p - Vec<3>(prepared.mesh().vertices.col(patch.loop[(i + 1) % n]))).norm() +
                                             (p - Vec<3>(prepared.mesh().vertices.col(patch.loop[(i + n - 1) % n]))).norm());
    }
    for (Eigen::Index k = 0; k < patch.vertices.cols(); ++k) {
      added_.push_back(patch.vertices.col(k));
      distance_.push_back(boundaryDistance(added_.back()));
      scale_.push_back(patch.meanEdgeLength);
    }
    for (Eigen::Index t = 0; t < patch.triangles.cols(); ++t)
      addTriangle({patch.triangles(0, t), patch.triangles(1, t), patch.triangles(2, t)});
    for (std::size_t i = 0; i < patch.loop.size(); ++i)
      boundary_.insert(edgeKey(patch.loop[i], patch.loop[(i + 1) % patch.loop.size()]));
  }

  std::size_t triangleCount() const { return triangles_.size(); }

  Vec<3> position(int id) const {
    return id < patch_.baseId ? Vec<3>(prepared_.mesh().vertices.col(id)) : added_[std::size_t(id - patch_.baseId)];
  }

  // Distance from x to the nearest boundary vertex when grading (else 0). O(boundary) per call:
  // called once per new vertex.
  double boundaryDistance(const Vec<3>& x) const {
    if (!(grading_ > 0)) return 0;
    double best = std::numeric_limits<double>::infinity();
    for (const Vec<3>& b : boundaryPoints_) best = std::min(best, (b - x).squaredNorm());
    return std::sqrt(best);
  }
  // The local edge length at a vertex for uniform refinement: a boundary vertex's is the mean of
  // its two boundary edges, a midpoint's the mean of its edge's ends (so short boundary edges get
  // small triangles next to them, not slivers).
  double scale(int id) const {
    if (id >= patch_.baseId) return scale_[std::size_t(id - patch_.baseId)];
    const auto it = boundaryScale_.find(id);
    return it == boundaryScale_.end() ? patch_.meanEdgeLength : it->second;
  }
  double distance(int id) const { return id < patch_.baseId ? 0.0 : distance_[std::size_t(id - patch_.baseId)]; }

  // The target edge length at x (see the constructor).
  double targetLength(const Vec<3>& x) const { return patch_.meanEdgeLength + grading_ * boundaryDistance(x); }

  // Interior edges longer than `factor` × the target length at their midpoint (the mean of their
  // ends' targets), longest relative to it first.
  std::vector<std::uint64_t> longEdges(double factor) const {
    std::vector<std::pair<double, std::uint64_t>> found;
    const double l = patch_.meanEdgeLength;
    for (const auto& [key, tris] : edges_) {
      if (boundary_.count(key)) continue;
      const int a = int(key >> 32), b = int(key & 0xffffffffu);
      const double target = grading_ > 0 ? l + grading_ * 0.5 * (distance(a) + distance(b)) : 0.5 * (scale(a) + scale(b));
      const double ratio = (position(a) - position(b)).norm() / target;
      if (ratio > factor) found.emplace_back(ratio, key);
    }
    std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) {
      return x.first != y.first ? x.first > y.first : x.second < y.second;
    });
    std::vector<std::uint64_t> keys;
    for (const auto& f : found) keys.push_back(f.second);
    return keys;
  }

  // Splits the edge at its midpoint: each adjacent patch triangle becomes two.
  // Not where the midpoint falls within l/4 of a triangle's opposite corner (a flat triangle: its
  // Delaunay flip is the fix; the split would start a cluster of ever closer vertices). Returns
  // whether it split.
  bool split(std::uint64_t key) {
    const auto it = edges_.find(key);
    if (it == edges_.end()) return false;
    const std::array<int, 2> tris = it->second;
    const int a = int(key >> 32), b = int(key & 0xffffffffu);
    const Vec<3> mid = 0.5 * (position(a) + position(b));
    for (int t : tris)
      if (t >= 0 && (position(std::get<2>(rotatedTo(t, a, b))) - mid).norm() < 0.125 * (scale(a) + scale(b))) return false;
    const int m = patch_.baseId + int(added_.size());
    added_.push_back(mid);
    distance_.push_back(boundaryDistance(added_.back()));
    scale_.push_back(0.5 * (scale(a) + scale(b)));
    for (int t : tris) {
      if (t < 0) continue;
      const auto [x, y, o] = rotatedTo(t, a, b);  // t = (x, y, o) with x → y the edge
      removeTriangle(t);
      setTriangle(t, {x, m, o});
      addTriangle({m, y, o});
    }
    return true;
  }

  // One pass of centroid insertion (Liepa 2003, with the target lengths in place of his averaged
  // scales): triangle (a, b, c) is split at its centroid m into three when √2 · |m − v| exceeds
  // both the target at m and the target at v for every corner v, and √2 × m's distance to the
  // nearest boundary vertex exceeds l. Returns the number of splits.
  int centroidPass() {
    const std::size_t count = triangles_.size();
    int splits = 0;
    for (std::size_t t = 0; t < count; ++t) {
      const Triangle tri = triangles_[t];
      const Vec<3> m = (position(tri[0]) + position(tri[1]) + position(tri[2])) / 3.0;
      const double dm = boundaryDistance(m), target = patch_.meanEdgeLength + grading_ * dm;
      bool dense = !(std::sqrt(2.0) * dm > 0.5 * patch_.meanEdgeLength);  // next to a boundary vertex
      for (int v : tri) {
        const double r = std::sqrt(2.0) * (m - position(v)).norm();
        dense = dense || !(r > target && r > patch_.meanEdgeLength + grading_ * distance(v));
      }
      if (dense) continue;
      const int id = patch_.baseId + int(added_.size());
      added_.push_back(m);
      distance_.push_back(dm);
      scale_.push_back(patch_.meanEdgeLength);
      removeTriangle(int(t));
      setTriangle(int(t), {tri[0], tri[1], id});
      addTriangle({tri[1], tri[2], id});
      addTriangle({tri[2], tri[0], id});
      ++splits;
      tick();
    }
    return splits;
  }

  // One pass of smart Laplacian smoothing: each new vertex moves to the mean of its neighbours
  // when that raises the smallest angle of its triangles and turns none of them over by more than
  // 90°; only vertices whose sharpest corner has a cosine above `onlyAbove` are tried. Returns the
  // number of vertices moved.
  int smoothPass(double onlyAbove = -1) {
    std::vector<std::vector<int>> around(added_.size());  // triangles at each new vertex
    for (std::size_t t = 0; t < triangles_.size(); ++t)
      for (int v : triangles_[t])
        if (v >= patch_.baseId) around[std::size_t(v - patch_.baseId)].push_back(int(t));
    int moved = 0;
    for (std::size_t k = 0; k < added_.size(); ++k) {
      if (around[k].empty()) continue;
      const int id = patch_.baseId + int(k);
      Vec<3> mean = Vec<3>::Zero();
      double before = -1, after = -1;  // largest corner cosine: the smallest angle, reversed
      std::vector<Vec<3>> normals;
      for (int t : around[k]) {
        const Triangle& tri = triangles_[std::size_t(t)];
        for (int v : tri) mean += v == id ? Vec<3>::Zero() : Vec<3>(0.5 * position(v));  // each neighbour twice
        before = std::max(before, sharpestCosine(tri[0], tri[1], tri[2]));
        normals.push_back((position(tri[1]) - position(tri[0])).cross(position(tri[2]) - position(tri[0])));
      }
      mean /= double(around[k].size());
      if (!(before > onlyAbove)) continue;
      const Vec<3> old = added_[k];
      added_[k] = mean;
      bool turned = false;
      for (std::size_t i = 0; i < around[k].size(); ++i) {
        const Triangle& tri = triangles_[std::size_t(around[k][i])];
        after = std::max(after, sharpestCosine(tri[0], tri[1], tri[2]));
        turned = turned || !((position(tri[1]) - position(tri[0])).cross(position(tri[2]) - position(tri[0])).dot(normals[i]) > 0);
      }
      if (turned || !(after < before - 1e-12)) {
        added_[k] = old;
        continue;
      }
      distance_[k] = boundaryDistance(mean);
      ++moved;
      tick();
    }
    return moved;
  }

  // One sweep of angle-improving flips (delaunay false) or of Delaunay flips (the two angles
  // opposite the edge sum to more than π); returns how many were made.
  int flipSweep(bool delaunay = false) {
    std::vector<std::uint64_t> keys;
    keys.reserve(edges_.size());
    for (const auto& [key, tris] : edges_)
      if (!boundary_.count(key) && tris[0] >= 0 && tris[1] >= 0) keys.push_back(key);
    std::sort(keys.begin(), keys.end());  // a fixed order: the result does not depend on hashing
    int flips = 0;
    for (std::uint64_t key : keys) {
      flips += tryFlip(key, delaunay);
      tick();
    }
    return flips;
  }

  // Called every 4096 elementary steps (splits, flips tried, vertices moved): the caller's progress
  // report between the rounds would come too seldom on large patches.
  std::function<void()> onTick;

  void writeBack() {
    patch_.vertices.resize(3, Eigen::Index(added_.size()));
    for (std::size_t k = 0; k < added_.size(); ++k) patch_.vertices.col(Eigen::Index(k)) = added_[k];
    patch_.triangles.resize(3, Eigen::Index(triangles_.size()));
    patch_.vertexNormals = Eigen::Matrix3Xd::Zero(3, Eigen::Index(added_.size()));
    for (std::size_t t = 0; t < triangles_.size(); ++t) {
      const auto& tri = triangles_[t];
      const Vec<3> normal = (position(tri[1]) - position(tri[0])).cross(position(tri[2]) - position(tri[0]));
      for (int c = 0; c < 3; ++c) {
        patch_.triangles(c, Eigen::Index(t)) = tri[c];
        if (tri[c] >= patch_.baseId) patch_.vertexNormals.col(tri[c] - patch_.baseId) += normal;
      }
    }
    for (Eigen::Index k = 0; k < patch_.vertexNormals.cols(); ++k) patch_.vertexNormals.col(k).normalize();
  }

 private:
  using Triangle = std::array<int, 3>;

  std::tuple<int, int, int> rotatedTo(int t, int a, int b) const {
    const Triangle& tri = triangles_[std::size_t(t)];
    for (int c = 0; c < 3; ++c) {
      const int x = tri[c], y = tri[(c + 1) % 3];
      if ((x == a && y == b) || (x == b && y == a)) return {x, y, tri[(c + 2) % 3]};
    }
    return {a, b, tri[0]};  // unreachable for an edge of t
  }

  void link(int u, int v, int t) {
    auto [it, inserted] = edges_.try_emplace(edgeKey(u, v), std::array<int, 2>{t, -1});
    if (!inserted) (it->second[0] < 0 ? it->second[0] : it->second[1]) = t;
  }
  void unlink(int u, int v, int t) {
    const auto it = edges_.find(edgeKey(u, v));
    if (it == edges_.end()) return;
    for (int& s : it->second)
      if (s == t) s = -1;
    if (it->second[0] < 0 && it->second[1] < 0) edges_.erase(it);
  }
  void addTriangle(const Triangle& tri) {
    triangles_.push_back(tri);
    setTriangle(int(triangles_.size()) - 1, tri);
  }
  void setTriangle(int t, const Triangle& tri) {
    triangles_[std::size_t(t)] = tri;
    for (int c = 0; c < 3; ++c) link(tri[c], tri[(c + 1) % 3], t);
  }
  void removeTriangle(int t) {
    const Triangle tri = triangles_[std::size_t(t)];
    for (int c = 0; c < 3; ++c) unlink(tri[c], tri[(c + 1) % 3], t);
  }

  bool edgeExists(int u, int v) const {
    if (edges_.count(edgeKey(u, v))) return true;
    if (u >= patch_.baseId || v >= patch_.baseId) return false;
    const std::vector<int> around = prepared_.neighbours(u);
    return std::binary_search(around.begin(), around.end(), v);
  }

  // The cosine of the triangle's smallest angle (the largest of its corners' cosines).
  double sharpestCosine(int a, int b, int c) const {
    const Vec<3> pa = position(a), pb = position(b), pc = position(c);
    return std::max({cornerCosine(pa, pb, pc), cornerCosine(pb, pa, pc), cornerCosine(pc, pa, pb)});
  }

  // Flips edge (a, b) of t1 = (a, b, c), t2 = (b, a, d) to (c, d) when the smaller minimum angle
  // grows and the new triangles face the same way as the old pair.
  bool tryFlip(std::uint64_t key, bool delaunay) {
    const auto it = edges_.find(key);
    if (it == edges_.end() || it->second[0] < 0 || it->second[1] < 0) return false;
    const int t1 = it->second[0], t2 = it->second[1];
    const int u = int(key >> 32), w = int(key & 0xffffffffu);
    const auto [a, b, c] = rotatedTo(t1, u, w);
    const auto [b2, a2, d] = rotatedTo(t2, u, w);
    if (b2 != b || a2 != a || c == d || edgeExists(c, d)) return false;
    const Vec<3> pa = position(a), pb = position(b), pc = position(c), pd = position(d);
    if (delaunay) {
      const double opposite = std::acos(std::clamp(cornerCosine(pc, pa, pb), -1.0, 1.0)) +
                              std::acos(std::clamp(cornerCosine(pd, pa, pb), -1.0, 1.0));
      if (!(opposite > std::numbers::pi + 1e-9)) return false;
    } else {
      const double before = std::max(sharpestCosine(a, b, c), sharpestCosine(b, a, d));
      const double after = std::max(sharpestCosine(c, a, d), sharpestCosine(d, b, c));
      if (!(after < before - 1e-12)) return false;
    }
    const Vec<3> old = (pb - pa).cross(pc - pa) + (pa - pb).cross(pd - pb);
    const Vec<3> n1 = (pa - pc).cross(pd - pc), n2 = (pb - pd).cross(pc - pd);
    if (!(n1.dot(old) > 0 && n2.dot(old) > 0)) return false;
    removeTriangle(t1);
    removeTriangle(t2);
    setTriangle(t1, {c, a, d});
    setTriangle(t2, {d, b, c});
    return true;
  }

  void tick() {
    if (onTick && ++ticks_ % 4096 == 0) onTick();
  }

  const PreparedMesh& prepared_;
  HolePatch& patch_;
  std::uint64_t ticks_ = 0;
  double grading_ = 0;
  std::vector<Vec<3>> boundaryPoints_;
  std::vector<Vec<3>> added_;
  std::vector<double> distance_;  // of each added vertex to the boundary (0 when not grading)
  std::vector<double> scale_;     // of each added vertex (see scale)
  std::unordered_map<int, double> boundaryScale_;
  std::vector<Triangle> triangles_;
  std::unordered_map<std::uint64_t, std::array<int, 2>> edges_;  // → up to two patch triangles
  std::unordered_set<std::uint64_t> boundary_;
};

// refinePatch's rounds on the editable patch (see there).
bool refineEditable(EditablePatch& editable, HolePatch& patch, double grading,
                    const std::function<bool(double)>& progress, double& reached) {
  const double l = patch.meanEdgeLength;
  if (!(l > 0)) return true;
  // Equilateral triangles of the target side at each first triangle's centroid: the count the
  // refinement heads for.
  double expected = 0;
  for (Eigen::Index t = 0; t < patch.triangles.cols(); ++t) {
    const Vec<3> p0 = editable.position(patch.triangles(0, t)), p1 = editable.position(patch.triangles(1, t)),
                 p2 = editable.position(patch.triangles(2, t));
    const double h = editable.targetLength((p0 + p1 + p2) / 3.0);
    expected += 0.5 * (p1 - p0).cross(p2 - p0).norm() / (std::sqrt(3.0) / 4.0 * h * h);
  }
  expected = std::max(1.0, expected);
  // Relaxed first: an ear of the first triangulation along a straight or gently curved run of
  // the boundary has its centroid, or the midpoint of its long edge, next to (or on) the
  // boundary vertex between its ends.
  for (int pass = 0; pass < 16 && editable.flipSweep(true) > 0; ++pass) {
  }
  // Graded: centroid insertion with Delaunay relaxation (midpoint splits would crowd vertices
  // where the long edges of the first triangulation's fans meet the boundary).
  for (int round = 0; grading > 0 && round < 64; ++round) {
    const int splits = editable.centroidPass();
    for (int pass = 0; pass < 16 && editable.flipSweep(true) > 0; ++pass) {
    }
    for (int pass = 0; pass < 2; ++pass) {
      editable.smoothPass();
      editable.flipSweep(true);
    }
    reached = std::min(1.0, double(editable.triangleCount()) / expected);
    if (progress && !progress(reached)) return false;
    if (splits == 0) break;
  }
  for (int round = 0; grading == 0 && round < 64; ++round) {
    const std::vector<std::uint64_t> tooLong = editable.longEdges(4.0 / 3.0);
    if (tooLong.empty()) break;
    int splits = 0;
    for (std::uint64_t key : tooLong) splits += editable.split(key);
    for (int pass = 0; pass < 16 && editable.flipSweep(true) > 0; ++pass) {
    }
    if (splits == 0) break;
    reached = std::min(1.0, double(editable.triangleCount()) / expected);
    if (progress && !progress(reached)) return false;
  }
  for (int pass = 0; pass < 8 && editable.flipSweep() > 0; ++pass) {
    if (progress && !progress(1.0)) return false;
  }
  editable.writeBack();
  return true;
}

}  // namespace

bool refinePatch(const PreparedMesh& prepared, HolePatch& patch, const std::function<bool(double)>& progress,
                 double grading) {
  EditablePatch editable(prepared, patch, grading);
  struct Stopped {};  // thrown by onTick when progress says stop
  double reached = 0;  // the last fraction reported
  if (progress) editable.onTick = [&] {
    if (!progress(reached)) throw Stopped{};
  };
  try {
    return refineEditable(editable, patch, grading, progress, reached);
  } catch (const Stopped&) {
    return false;
  }
}

int improvePatchAngles(const PreparedMesh& prepared, HolePatch& patch, int passes) {
  EditablePatch editable(prepared, patch);
  int flips = 0;
  const double fiveDegrees = std::cos(5.0 * std::numbers::pi / 180.0);
  for (int pass = 0; pass < passes; ++pass) {
    const int made = editable.flipSweep();
    flips += made;
    if (made + editable.smoothPass(fiveDegrees) == 0) break;
  }
  editable.writeBack();
  return flips;
}

}  // namespace hermite
