#include "core/mesh/advancing_front.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <unordered_set>

#include <Eigen/Geometry>

namespace hermite {

namespace {

constexpr double kDeg = M_PI / 180.0;

// The front under construction: positions and normals of original and new vertices by id.
struct Front {
  const PreparedMesh& prepared;
  HolePatch& patch;
  std::vector<Eigen::Vector3d> newPositions, newNormals;
  std::vector<std::array<int, 3>> triangles;
  std::unordered_set<std::uint64_t> edges;  // every edge touching the hole so far

  Eigen::Vector3d position(int id) const {
    return id < patch.baseId ? Eigen::Vector3d(prepared.mesh().vertices.col(id)) : newPositions[static_cast<size_t>(id - patch.baseId)];
  }
  Eigen::Vector3d normal(int id) const {
    return id < patch.baseId ? Eigen::Vector3d(prepared.normals().col(id)) : newNormals[static_cast<size_t>(id - patch.baseId)];
  }
  // A new vertex's normal (the one its angles are measured about) is the inverse-square-distance
  // mean of the hole boundary's normals: it turns with the surface across a wide hole, where the
  // creating vertex's normal would go stale ring after ring.
  int addVertex(const Eigen::Vector3d& x, const Eigen::Vector3d& fallback) {
    Eigen::Vector3d n = Eigen::Vector3d::Zero();
    const double eps = 1e-6 * patch.meanEdgeLength * patch.meanEdgeLength;
    for (int b : patch.loop) n += prepared.normals().col(b) / ((prepared.mesh().vertices.col(b) - x).squaredNorm() + eps);
    newPositions.push_back(x);
    newNormals.push_back(n.norm() > 0 && n.allFinite() ? Eigen::Vector3d(n.normalized()) : fallback);
    return patch.baseId + static_cast<int>(newPositions.size()) - 1;
  }
  // Σ (π − interior angle) over a front: 2π minus the enclosed curvature for a front with the
  // hole on its left, about −2π for one turned inside out.
  double turning(const std::vector<int>& front) const {
    const size_t n = front.size();
    double sum = 0;
    for (size_t i = 0; i < n; ++i) {
      Eigen::Vector3d e1, e1p;
      sum += M_PI - frontAngleAt(front[(i + n - 1) % n], front[i], front[(i + 1) % n], e1, e1p);
    }
    return sum;
  }
  double frontAngleAt(int p, int v, int q, Eigen::Vector3d& e1, Eigen::Vector3d& e1p) const;
  void addTriangle(int a, int b, int c) {
    triangles.push_back({a, b, c});
    edges.insert(edgeKey(a, b));
    edges.insert(edgeKey(b, c));
    edges.insert(edgeKey(c, a));
  }
};

// Interior angle at v between the front edges to q (next) and p (previous), on the hole's side:
// the counter-clockwise turn about n from (q − v) to (p − v), both projected onto the plane ⊥ n.
// Also returns the projected unit direction to q and the in-plane unit normal n × ê₁.
double frontAngle(const Eigen::Vector3d& p, const Eigen::Vector3d& v, const Eigen::Vector3d& q, Eigen::Vector3d n,
                  Eigen::Vector3d& e1Unit, Eigen::Vector3d& e1Perp) {
  if (!(n.norm() > 0)) n = (q - v).cross(p - v);  // no normal: the corner's own plane
  n.normalize();
  Eigen::Vector3d e1 = (q - v) - (q - v).dot(n) * n, e2 = (p - v) - (p - v).dot(n) * n;
  if (!(e1.norm() > 0)) e1 = q - v;
  e1Unit = e1.normalized();
  e1Perp = n.cross(e1Unit);
  double a = std::atan2(n.dot(e1.cross(e2)), e1.dot(e2));
  if (a < 0) a += 2 * M_PI;
  return a;
}

double Front::frontAngleAt(int p, int v, int q, Eigen::Vector3d& e1, Eigen::Vector3d& e1p) const {
  return frontAngle(position(p), position(v), position(q), normal(v), e1, e1p);
}

// Closing front vertex i against front vertex j splits the front into j … i−1 and i+1 … j.
void splitFront(const std::vector<int>& front, int i, int j, std::vector<int>& a, std::vector<int>& b) {
  const int n = static_cast<int>(front.size());
  a.clear();
  b.clear();
  for (int k = j;; k = (k + 1) % n) {
    a.push_back(front[k]);
    if (k == (i + n - 1) % n) break;
  }
  for (int k = (i + 1) % n;; k = (k + 1) % n) {
    b.push_back(front[k]);
    if (k == j) break;
  }
}

// Whether segments ab and cd cross at a point inside both (touching at an end does not count).
bool segmentsCross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  auto orient = [](const Eigen::Vector2d& o, const Eigen::Vector2d& x, const Eigen::Vector2d& y) {
    const Eigen::Vector2d u = x - o, w = y - o;
    return u.x() * w.y() - u.y() * w.x();
  };
  const double d1 = orient(c, d, a), d2 = orient(c, d, b), d3 = orient(a, b, c), d4 = orient(a, b, d);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

}  // namespace

HolePatch advancingFront(const PreparedMesh& prepared, const BoundaryLoop& loop, const HoleFillOptions& options) {
  HolePatch patch;
  patch.loop = loop;
  patch.baseId = prepared.mesh().vertexCount();
  Front F{prepared, patch, {}, {}, {}, {}};
  const int n0 = static_cast<int>(loop.size());
  if (n0 < 3) {
    patch.failure = "a boundary loop of fewer than 3 vertices";
    return patch;
  }
  // The front runs against the triangles' boundary direction, so the hole is on its left and a
  // front edge (a → b) is closed by a triangle (a, b, ·).
  std::vector<int> front(loop.rbegin(), loop.rend());
  double l = 0;
  for (int i = 0; i < n0; ++i) l += (F.position(loop[i]) - F.position(loop[(i + 1) % n0])).norm();
  l /= n0;
  patch.meanEdgeLength = l;
  for (int i = 0; i < n0; ++i)
    for (int j = i + 1; j < n0; ++j)
      patch.diameter = std::max(patch.diameter, (F.position(loop[i]) - F.position(loop[j])).norm());
  for (int v : loop)
    for (const int* t = prepared.trianglesBegin(v); t != prepared.trianglesEnd(v); ++t)
      for (int k = 0; k < 3; ++k)
        F.edges.insert(edgeKey(prepared.mesh().triangles(k, *t), prepared.mesh().triangles((k + 1) % 3, *t)));

  // A disc bounded by n edges of length l takes about n²/11 + n steps (one per triangle or
  // vertex pair); the bound leaves room for ~3× that.
  const long maxSteps = static_cast<long>(std::max(0.0, options.frontStepFactor) * (0.25 * n0 * n0 + 40.0 * n0)) + 10;
  struct CachedAngle {
    int prev = -1, next = -1;
    double angle = 0;
  };
  std::unordered_map<int, CachedAngle> angleCache;
  const long maxNewVertices = static_cast<long>(n0) * n0 / 4 + 4L * n0;
  // Fronts still open: a merge splits one front in two (the hole pinched into two holes).
  std::vector<std::vector<int>> fronts;
  fronts.push_back(std::move(front));
  std::vector<std::pair<double, int>> order;
  long step = 0;
  while (!fronts.empty() && patch.failure.empty()) {
    std::vector<int>& cur = fronts.back();
    if (cur.size() <= 2) {  // two opposite edges of one segment: nothing left to close
      fronts.pop_back();
      continue;
    }
    if (cur.size() == 3) {
      F.addTriangle(cur[0], cur[1], cur[2]);
      fronts.pop_back();
      continue;
    }
    if (step >= maxSteps) {
      patch.failure = "the advancing front did not close within " + std::to_string(maxSteps) + " steps";
      break;
    }
    // A front that grows instead of closing has folded over itself (the new vertices land outside
    // the hole); a disc bounded by n edges of length l needs about n²/(4π√3) new vertices.
    if (static_cast<long>(cur.size()) > 2L * n0 + 10 || static_cast<long>(F.newPositions.size()) > maxNewVertices) {
      patch.failure = "the advancing front folded over itself (it grew to " + std::to_string(cur.size()) +
                      " vertices, " + std::to_string(F.newPositions.size()) + " new)";
      break;
    }
    ++step;
    const int n = static_cast<int>(cur.size());
    // Angles depend only on a vertex and its two front neighbours (positions never move while
    // the front advances): cached, recomputed where an operation changed a neighbour.
    order.clear();
    for (int i = 0; i < n; ++i) {
      const int p = cur[(i + n - 1) % n], v = cur[i], q = cur[(i + 1) % n];
      CachedAngle& c = angleCache[v];
      if (c.prev != p || c.next != q) {
        Eigen::Vector3d e1, e1p;
        c = {p, q, frontAngle(F.position(p), F.position(v), F.position(q), F.normal(v), e1, e1p)};
      }
      order.emplace_back(c.angle, i);
    }
    // Σ(π − angle) is 2π minus the curvature the front encloses; near −2π it runs the wrong way
    // round: from the start, the boundary is an outer one (an open surface's rim, or a hole wider
    // than a hemisphere); later, the front has folded. Either way it would only grow.
    double turning = 0;
    for (const auto& oa : order) turning += M_PI - oa.first;
    if (turning < -M_PI) {  // ≈ −2π when inverted; a margin for the normals' error on curved fronts
      patch.failure = step == 1 ? "the boundary turns the wrong way round (an open surface's outer rim, or a hole wider "
                                  "than a hemisphere): not a hole the front can close"
                                : "the advancing front folded over itself (it turns the wrong way round)";
      break;
    }
    // The smallest angle first; the others are sorted only when it cannot be taken.
    std::iter_swap(order.begin(), std::min_element(order.begin(), order.end()));
    bool done = false;
    for (size_t candidate = 0; candidate < order.size(); ++candidate) {
      if (candidate == 1) std::sort(order.begin() + 1, order.end());
      const double angle = order[candidate].first;
      const int i = order[candidate].second;
      const int p = cur[(i + n - 1) % n], v = cur[i], q = cur[(i + 1) % n];
      const Eigen::Vector3d xv = F.position(v);
      Eigen::Vector3d e1, e1p;
      frontAngle(F.position(p), xv, F.position(q), F.normal(v), e1, e1p);
      const Eigen::Vector3d normalV = e1.cross(e1p).normalized();  // the normal the angle was measured about
      auto dir = [&](double a) { return Eigen::Vector3d(std::cos(a) * e1 + std::sin(a) * e1p); };
      // Geometric validity in v's tangent plane: a new edge (given by its end points; ids < 0 are
      // new vertices) must not cross a front edge it does not share an end with.
      auto plane = [&](const Eigen::Vector3d& x) { return Eigen::Vector2d((x - xv).dot(e1), (x - xv).dot(e1p)); };
      auto crossesFront = [&](int ia, const Eigen::Vector3d& a3, int ib, const Eigen::Vector3d& b3) {
        const Eigen::Vector2d a2 = plane(a3), b2 = plane(b3);
        for (int k = 0; k < n; ++k) {
          const int c = cur[k], d = cur[(k + 1) % n];
          if (c == ia || c == ib || d == ia || d == ib) continue;
          if (segmentsCross(a2, b2, plane(F.position(c)), plane(F.position(d)))) return true;
        }
        return false;
      };
      auto clipValid = [&] {
        return !F.edges.count(edgeKey(p, q)) && !crossesFront(p, F.position(p), q, F.position(q));
      };
      // A merge with front vertex j (not p, v, q): every edge new, or, for p's predecessor and
      // q's successor, the front edge it closes; no new edge crossing the front.
      auto mergeValid = [&](int j) {
        const int u = cur[j];
        if (u == p || u == v || u == q) return false;
        if (F.edges.count(edgeKey(p, u)) && j != (i + n - 2) % n) return false;
        if (F.edges.count(edgeKey(u, q)) && j != (i + 2) % n) return false;
        if (F.edges.count(edgeKey(v, u))) return false;
        const Eigen::Vector3d xu = F.position(u);
        if (crossesFront(p, F.position(p), u, xu) || crossesFront(u, xu, q, F.position(q)) || crossesFront(v, xv, u, xu))
          return false;
        // Both fronts it leaves must still turn counter-clockwise about the surface (hole on
        // their left): a merge across the outside would leave one inside out, growing forever.
        std::vector<int> a, b;
        splitFront(cur, i, j, a, b);
        return (a.size() < 3 || F.turning(a) > 0) && (b.size() < 3 || F.turning(b) > 0);
      };
      // The valid merge nearest to x within radius, or -1.
      auto nearestMerge = [&](const Eigen::Vector3d& x, double radius) {
        int best = -1;
        for (int j = 0; j < n; ++j) {
          const double d = (F.position(cur[j]) - x).norm();
          if (d < radius && mergeValid(j)) best = j, radius = d;
        }
        return best;
      };
      auto newVertexValid = [&](const Eigen::Vector3d& x) {
        return !crossesFront(p, F.position(p), -1, x) && !crossesFront(-1, x, q, F.position(q)) &&
               !crossesFront(v, xv, -1, x);
      };
      const bool small = n <= options.clipFrontSize;
      const Eigen::Vector3d x1 = xv + l * dir(angle / 3), x2 = xv + l * dir(2 * angle / 3), xm = xv + l * dir(angle / 2);
      enum class Op { None, Clip, One, Two, Merge } op = Op::None;
      int mergeAt = -1;
      if (angle < 75 * kDeg || (small && angle < M_PI)) {
        if (clipValid()) op = Op::Clip;
      } else {
        // A front vertex near where the new vertex would go: use it instead (the front splits).
        mergeAt = nearestMerge(xm, options.mergeDistance * l);
        if (mergeAt >= 0) op = Op::Merge;
        else if (angle > 135 * kDeg && !crossesFront(p, F.position(p), -1, x2) && !crossesFront(-1, x2, -1, x1) &&
                 !crossesFront(-1, x1, q, F.position(q)) && !crossesFront(v, xv, -1, x1) && !crossesFront(v, xv, -1, x2))
          op = Op::Two;
        else if (angle <= 135 * kDeg && newVertexValid(xm))
          op = Op::One;
        else if ((mergeAt = nearestMerge(xm, 2 * l)) >= 0)
          op = Op::Merge;
        else if (angle < M_PI && clipValid())
          op = Op::Clip;
      }
      if (op == Op::None) continue;  // nothing valid here: try the next smallest angle
      if (op == Op::Clip) {
        F.addTriangle(p, v, q);
        cur.erase(cur.begin() + i);
      } else if (op == Op::Merge) {
        // Close v against the existing front vertex u: triangles (p, v, u), (u, v, q); the front
        // splits into u … p and q … u.
        const int u = cur[mergeAt];
        F.addTriangle(p, v, u);
        F.addTriangle(u, v, q);
        std::vector<int> a, b;
        splitFront(cur, i, mergeAt, a, b);
        cur = std::move(a);
        fronts.push_back(std::move(b));
      } else if (op == Op::One) {
        const int w = F.addVertex(xm, normalV);
        F.addTriangle(p, v, w);
        F.addTriangle(w, v, q);
        cur[i] = w;
      } else {
        const int w1 = F.addVertex(x1, normalV);
        const int w2 = F.addVertex(x2, normalV);
        F.addTriangle(p, v, w2);
        F.addTriangle(w2, v, w1);
        F.addTriangle(w1, v, q);
        cur[i] = w1;
        cur.insert(cur.begin() + i, w2);  // front: p → w2 → w1 → q
      }
      done = true;
      break;
    }
    if (!done) patch.failure = "no front vertex can be advanced without repeating an edge or crossing the front";
  }
  patch.closed = fronts.empty();
  patch.frontSteps = static_cast<int>(step);
  const int K = static_cast<int>(F.newPositions.size());
  patch.vertices.resize(3, K);
  patch.vertexNormals.resize(3, K);
  for (int k = 0; k < K; ++k) {
    patch.vertices.col(k) = F.newPositions[k];
    patch.vertexNormals.col(k) = F.newNormals[k];
  }
  patch.triangles.resize(3, static_cast<Eigen::Index>(F.triangles.size()));
  for (size_t t = 0; t < F.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) patch.triangles(k, static_cast<Eigen::Index>(t)) = F.triangles[t][k];
  return patch;
}

}  // namespace hermite
