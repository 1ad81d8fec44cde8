// Longest-edge splitting and angle-improving flips of a hole patch (patch_refinement.h).

#include "core/mesh/patch_refinement.h"

#include <algorithm>
#include <array>
#include <cmath>
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
  EditablePatch(const PreparedMesh& prepared, HolePatch& patch) : prepared_(prepared), patch_(patch) {
    for (Eigen::Index k = 0; k < patch.vertices.cols(); ++k) added_.push_back(patch.vertices.col(k));
    for (Eigen::Index t = 0; t < patch.triangles.cols(); ++t)
      addTriangle({patch.triangles(0, t), patch.triangles(1, t), patch.triangles(2, t)});
    for (std::size_t i = 0; i < patch.loop.size(); ++i)
      boundary_.insert(edgeKey(patch.loop[i], patch.loop[(i + 1) % patch.loop.size()]));
  }

  std::size_t triangleCount() const { return triangles_.size(); }

  Vec<3> position(int id) const {
    return id < patch_.baseId ? Vec<3>(prepared_.mesh().vertices.col(id)) : added_[std::size_t(id - patch_.baseId)];
  }

  // Interior edges longer than `threshold`, longest first.
  std::vector<std::uint64_t> longEdges(double threshold) const {
    std::vector<std::pair<double, std::uint64_t>> found;
    for (const auto& [key, tris] : edges_) {
      if (boundary_.count(key)) continue;
      const double length = (position(int(key >> 32)) - position(int(key & 0xffffffffu))).norm();
      if (length > threshold) found.emplace_back(length, key);
    }
    std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    std::vector<std::uint64_t> keys;
    for (const auto& f : found) keys.push_back(f.second);
    return keys;
  }

  // Splits the edge at its midpoint: each adjacent patch triangle becomes two.
  void split(std::uint64_t key) {
    const auto it = edges_.find(key);
    if (it == edges_.end()) return;
    const std::array<int, 2> tris = it->second;
    const int a = int(key >> 32), b = int(key & 0xffffffffu);
    const int m = patch_.baseId + int(added_.size());
    added_.push_back(0.5 * (position(a) + position(b)));
    for (int t : tris) {
      if (t < 0) continue;
      const auto [x, y, o] = rotatedTo(t, a, b);  // t = (x, y, o) with x → y the edge
      removeTriangle(t);
      setTriangle(t, {x, m, o});
      addTriangle({m, y, o});
    }
  }

  // One sweep of angle-improving flips; returns how many were made.
  int flipSweep() {
    std::vector<std::uint64_t> keys;
    keys.reserve(edges_.size());
    for (const auto& [key, tris] : edges_)
      if (!boundary_.count(key) && tris[0] >= 0 && tris[1] >= 0) keys.push_back(key);
    std::sort(keys.begin(), keys.end());  // a fixed order: the result does not depend on hashing
    int flips = 0;
    for (std::uint64_t key : keys) flips += tryFlip(key);
    return flips;
  }

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
  bool tryFlip(std::uint64_t key) {
    const auto it = edges_.find(key);
    if (it == edges_.end() || it->second[0] < 0 || it->second[1] < 0) return false;
    const int t1 = it->second[0], t2 = it->second[1];
    const int u = int(key >> 32), w = int(key & 0xffffffffu);
    const auto [a, b, c] = rotatedTo(t1, u, w);
    const auto [b2, a2, d] = rotatedTo(t2, u, w);
    if (b2 != b || a2 != a || c == d || edgeExists(c, d)) return false;
    const double before = std::max(sharpestCosine(a, b, c), sharpestCosine(b, a, d));
    const double after = std::max(sharpestCosine(c, a, d), sharpestCosine(d, b, c));
    if (!(after < before - 1e-12)) return false;
    const Vec<3> pa = position(a), pb = position(b), pc = position(c), pd = position(d);
    const Vec<3> old = (pb - pa).cross(pc - pa) + (pa - pb).cross(pd - pb);
    const Vec<3> n1 = (pa - pc).cross(pd - pc), n2 = (pb - pd).cross(pc - pd);
    if (!(n1.dot(old) > 0 && n2.dot(old) > 0)) return false;
    removeTriangle(t1);
    removeTriangle(t2);
    setTriangle(t1, {c, a, d});
    setTriangle(t2, {d, b, c});
    return true;
  }

  const PreparedMesh& prepared_;
  HolePatch& patch_;
  std::vector<Vec<3>> added_;
  std::vector<Triangle> triangles_;
  std::unordered_map<std::uint64_t, std::array<int, 2>> edges_;  // → up to two patch triangles
  std::unordered_set<std::uint64_t> boundary_;
};

double patchArea(const EditablePatch& e, const HolePatch& patch) {
  double area = 0;
  for (Eigen::Index t = 0; t < patch.triangles.cols(); ++t) {
    const Vec<3> p0 = e.position(patch.triangles(0, t)), p1 = e.position(patch.triangles(1, t)),
                 p2 = e.position(patch.triangles(2, t));
    area += 0.5 * (p1 - p0).cross(p2 - p0).norm();
  }
  return area;
}

}  // namespace

bool refinePatch(const PreparedMesh& prepared, HolePatch& patch, const std::function<bool(double)>& progress) {
  EditablePatch editable(prepared, patch);
  const double l = patch.meanEdgeLength;
  if (!(l > 0)) return true;
  // Equilateral triangles of side l: the count the refinement heads for.
  const double expected = std::max(1.0, patchArea(editable, patch) / (std::sqrt(3.0) / 4.0 * l * l));
  for (int round = 0; round < 64; ++round) {
    const std::vector<std::uint64_t> tooLong = editable.longEdges(4.0 / 3.0 * l);
    if (tooLong.empty()) break;
    for (std::uint64_t key : tooLong) editable.split(key);
    editable.flipSweep();
    if (progress && !progress(std::min(1.0, double(editable.triangleCount()) / expected))) return false;
  }
  for (int pass = 0; pass < 8 && editable.flipSweep() > 0; ++pass) {
  }
  editable.writeBack();
  return true;
}

int improvePatchAngles(const PreparedMesh& prepared, HolePatch& patch, int passes) {
  EditablePatch editable(prepared, patch);
  int flips = 0;
  for (int pass = 0; pass < passes; ++pass) {
    const int made = editable.flipSweep();
    flips += made;
    if (made == 0) break;
  }
  editable.writeBack();
  return flips;
}

}  // namespace hermite
