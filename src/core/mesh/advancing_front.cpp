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

// A corner's angle, valid while its front neighbours are prev and next.
struct CachedAngle {
  int prev = -1, next = -1;
  double angle = 0;
};

// The step at a corner (advancing_front.h): clip it with one triangle, add one or two new
// vertices, merge with another front vertex, or none valid there.
enum class Op { None, Clip, One, Two, Merge };

struct Step {
  Op op = Op::None;
  int mergeAt = -1;            // front index of the vertex a merge closes against
  Eigen::Vector3d x1, x2, xm;  // new vertices at a third, two thirds and half of the angle
};

// Stores the loop's mean edge length l (the length of new edges) and diameter in the patch, and
// the mesh edges around the loop in F.edges (a new triangle must not repeat one).
void measureLoop(Front& F, const BoundaryLoop& loop) {
  const int n0 = static_cast<int>(loop.size());
  double l = 0;
  for (int i = 0; i < n0; ++i) l += (F.position(loop[i]) - F.position(loop[(i + 1) % n0])).norm();
  l /= n0;
  F.patch.meanEdgeLength = l;
  for (int i = 0; i < n0; ++i)
    for (int j = i + 1; j < n0; ++j)
      F.patch.diameter = std::max(F.patch.diameter, (F.position(loop[i]) - F.position(loop[j])).norm());
  const TriMesh& mesh = F.prepared.mesh();
  for (int v : loop)
    for (const int* t = F.prepared.trianglesBegin(v); t != F.prepared.trianglesEnd(v); ++t)
      for (int k = 0; k < 3; ++k) F.edges.insert(edgeKey(mesh.triangles(k, *t), mesh.triangles((k + 1) % 3, *t)));
}

// Front vertex i (v, between p and q) seen in v's tangent plane, with axes e1 towards q and
// e1p = n × e1: the validity tests of the steps that could advance the front there.
struct Corner {
  const Front& F;
  const std::vector<int>& cur;
  int n, i, p, v, q;
  Eigen::Vector3d xv, e1, e1p;

  Corner(const Front& front, const std::vector<int>& fr, int index)
      : F(front), cur(fr), n(static_cast<int>(fr.size())), i(index), p(fr[(index + n - 1) % n]), v(fr[index]),
        q(fr[(index + 1) % n]), xv(front.position(v)) {
    frontAngle(F.position(p), xv, F.position(q), F.normal(v), e1, e1p);
  }
  // The normal the angle was measured about: new vertices fall back to it.
  Eigen::Vector3d normal() const { return e1.cross(e1p).normalized(); }
  // The unit direction at angle a from e1 towards e1p.
  Eigen::Vector3d dir(double a) const { return Eigen::Vector3d(std::cos(a) * e1 + std::sin(a) * e1p); }
  Eigen::Vector2d plane(const Eigen::Vector3d& x) const { return Eigen::Vector2d((x - xv).dot(e1), (x - xv).dot(e1p)); }

  // Whether a new edge (given by its end points; ids < 0 are new vertices) crosses, in the
  // tangent plane, a front edge it does not share an end with.
  bool crossesFront(int ia, const Eigen::Vector3d& a3, int ib, const Eigen::Vector3d& b3) const {
    const Eigen::Vector2d a2 = plane(a3), b2 = plane(b3);
    for (int k = 0; k < n; ++k) {
      const int c = cur[k], d = cur[(k + 1) % n];
      if (c == ia || c == ib || d == ia || d == ib) continue;
      if (segmentsCross(a2, b2, plane(F.position(c)), plane(F.position(d)))) return true;
    }
    return false;
  }
  bool clipValid() const { return !F.edges.count(edgeKey(p, q)) && !crossesFront(p, F.position(p), q, F.position(q)); }
  // A merge with front vertex j (not p, v, q): every edge new, or, for p's predecessor and q's
  // successor, the front edge it closes; no new edge crossing the front.
  bool mergeValid(int j) const {
    const int u = cur[j];
    if (u == p || u == v || u == q) return false;
    if (F.edges.count(edgeKey(p, u)) && j != (i + n - 2) % n) return false;
    if (F.edges.count(edgeKey(u, q)) && j != (i + 2) % n) return false;
    if (F.edges.count(edgeKey(v, u))) return false;
    const Eigen::Vector3d xu = F.position(u);
    if (crossesFront(p, F.position(p), u, xu) || crossesFront(u, xu, q, F.position(q)) || crossesFront(v, xv, u, xu))
      return false;
    // Both fronts it leaves must still turn counter-clockwise about the surface (hole on their
    // left): a merge across the outside would leave one inside out, growing forever.
    std::vector<int> a, b;
    splitFront(cur, i, j, a, b);
    return (a.size() < 3 || F.turning(a) > 0) && (b.size() < 3 || F.turning(b) > 0);
  }
  // The front index of the valid merge nearest to x within radius, or -1.
  int nearestMerge(const Eigen::Vector3d& x, double radius) const {
    int best = -1;
    for (int j = 0; j < n; ++j) {
      const double d = (F.position(cur[j]) - x).norm();
      if (d < radius && mergeValid(j)) best = j, radius = d;
    }
    return best;
  }
  bool oneVertexValid(const Eigen::Vector3d& x) const {
    return !crossesFront(p, F.position(p), -1, x) && !crossesFront(-1, x, q, F.position(q)) &&
           !crossesFront(v, xv, -1, x);
  }
  // The new edges p–x2, x2–x1, x1–q, v–x1, v–x2 of a two-vertex step.
  bool twoVerticesValid(const Eigen::Vector3d& x1, const Eigen::Vector3d& x2) const {
    return !crossesFront(p, F.position(p), -1, x2) && !crossesFront(-1, x2, -1, x1) &&
           !crossesFront(-1, x1, q, F.position(q)) && !crossesFront(v, xv, -1, x1) && !crossesFront(v, xv, -1, x2);
  }
};

// The step the minimum-angle rules (advancing_front.h) take at a corner of this angle, falling
// back in turn to a wider merge and a clip when the preferred step is not valid.
Step chooseStep(const Corner& c, double angle, double l, const HoleFillOptions& options) {
  Step s;
  s.x1 = c.xv + l * c.dir(angle / 3);
  s.x2 = c.xv + l * c.dir(2 * angle / 3);
  s.xm = c.xv + l * c.dir(angle / 2);
  const bool small = c.n <= options.clipFrontSize;
  if (angle < 75 * kDeg || (small && angle < M_PI)) {
    if (c.clipValid()) s.op = Op::Clip;
    return s;
  }
  // A front vertex near where the new vertex would go: use it instead (the front splits).
  s.mergeAt = c.nearestMerge(s.xm, options.mergeDistance * l);
  if (s.mergeAt >= 0) s.op = Op::Merge;
  else if (angle > 135 * kDeg && c.twoVerticesValid(s.x1, s.x2)) s.op = Op::Two;
  else if (angle <= 135 * kDeg && c.oneVertexValid(s.xm)) s.op = Op::One;
  else if ((s.mergeAt = c.nearestMerge(s.xm, 2 * l)) >= 0) s.op = Op::Merge;
  else if (angle < M_PI && c.clipValid()) s.op = Op::Clip;
  return s;
}

// Takes step s at corner c of the last front (cur): adds its triangles and vertices and updates
// the front; a merge leaves the front's second part as a new last front.
void applyStep(Front& F, std::vector<std::vector<int>>& fronts, const Corner& c, const Step& s) {
  std::vector<int>& cur = fronts.back();
  const int p = c.p, v = c.v, q = c.q, i = c.i;
  if (s.op == Op::Clip) {
    F.addTriangle(p, v, q);
    cur.erase(cur.begin() + i);
  } else if (s.op == Op::Merge) {
    // Close v against the existing front vertex u: triangles (p, v, u), (u, v, q); the front
    // splits into u … p and q … u.
    const int u = cur[s.mergeAt];
    F.addTriangle(p, v, u);
    F.addTriangle(u, v, q);
    std::vector<int> a, b;
    splitFront(cur, i, s.mergeAt, a, b);
    cur = std::move(a);
    fronts.push_back(std::move(b));
  } else if (s.op == Op::One) {
    const int w = F.addVertex(s.xm, c.normal());
    F.addTriangle(p, v, w);
    F.addTriangle(w, v, q);
    cur[i] = w;
  } else {
    const int w1 = F.addVertex(s.x1, c.normal());
    const int w2 = F.addVertex(s.x2, c.normal());
    F.addTriangle(p, v, w2);
    F.addTriangle(w2, v, w1);
    F.addTriangle(w1, v, q);
    cur[i] = w1;
    cur.insert(cur.begin() + i, w2);  // front: p → w2 → w1 → q
  }
}

// The fronts still open over one hole (a merge splits one front in two: the hole pinched into
// two holes), advanced one step at a time within a step and growth budget.
class FrontAdvance {
 public:
  FrontAdvance(Front& F, const HoleFillOptions& options) : F_(F), options_(options) {
    n0_ = static_cast<int>(F.patch.loop.size());
    // A disc bounded by n edges of length l takes about n²/11 + n steps (one per triangle or
    // vertex pair); the bound leaves room for ~3× that.
    maxSteps_ = static_cast<long>(std::max(0.0, options.frontStepFactor) * (0.25 * n0_ * n0_ + 40.0 * n0_)) + 10;
    maxNewVertices_ = static_cast<long>(n0_) * n0_ / 4 + 4L * n0_;
    // The front runs against the triangles' boundary direction, so the hole is on its left and
    // a front edge (a → b) is closed by a triangle (a, b, ·).
    fronts_.emplace_back(F.patch.loop.rbegin(), F.patch.loop.rend());
  }

  // Advances until every front is closed or a safeguard stops it (the reason in failure).
  void run() {
    while (!fronts_.empty() && F_.patch.failure.empty()) {
      std::vector<int>& cur = fronts_.back();
      if (cur.size() <= 2) {  // two opposite edges of one segment: nothing left to close
        fronts_.pop_back();
        continue;
      }
      if (cur.size() == 3) {
        F_.addTriangle(cur[0], cur[1], cur[2]);
        fronts_.pop_back();
        continue;
      }
      F_.patch.failure = budgetFailure(cur);
      if (!F_.patch.failure.empty()) break;
      ++step_;
      F_.patch.failure = advance();
    }
  }
  bool closed() const { return fronts_.empty(); }
  long steps() const { return step_; }

 private:
  // Why the front must stop before another step: out of steps, or grown instead of closing.
  std::string budgetFailure(const std::vector<int>& cur) const {
    if (step_ >= maxSteps_) return "the advancing front did not close within " + std::to_string(maxSteps_) + " steps";
    // A front that grows instead of closing has folded over itself (the new vertices land
    // outside the hole); a disc bounded by n edges of length l needs about n²/(4π√3) new vertices.
    if (static_cast<long>(cur.size()) > 2L * n0_ + 10 || static_cast<long>(F_.newPositions.size()) > maxNewVertices_)
      return "the advancing front folded over itself (it grew to " + std::to_string(cur.size()) + " vertices, " +
             std::to_string(F_.newPositions.size()) + " new)";
    return {};
  }

  // Fills order_ with (angle, index) for every vertex of the last front. An angle depends only
  // on its vertex and the two front neighbours (positions never move while the front
  // advances), so it is cached and recomputed where a step changed a neighbour.
  void measureAngles() {
    const std::vector<int>& cur = fronts_.back();
    const int n = static_cast<int>(cur.size());
    order_.clear();
    for (int i = 0; i < n; ++i) {
      const int p = cur[(i + n - 1) % n], v = cur[i], q = cur[(i + 1) % n];
      CachedAngle& c = angleCache_[v];
      if (c.prev != p || c.next != q) {
        Eigen::Vector3d e1, e1p;
        c = {p, q, frontAngle(F_.position(p), F_.position(v), F_.position(q), F_.normal(v), e1, e1p)};
      }
      order_.emplace_back(c.angle, i);
    }
  }

  // One step on the last front at its smallest angle where a step is valid; the reason when
  // the front cannot advance.
  std::string advance() {
    measureAngles();
    // Σ(π − angle) is 2π minus the curvature the front encloses; near −2π it runs the wrong
    // way round: from the start, the boundary is an outer one (an open surface's rim, or a
    // hole wider than a hemisphere); later, the front has folded. Either way it would only grow.
    double turning = 0;
    for (const auto& oa : order_) turning += M_PI - oa.first;
    if (turning < -M_PI)  // ≈ −2π when inverted; a margin for the normals' error on curved fronts
      return step_ == 1 ? "the boundary turns the wrong way round (an open surface's outer rim, or a hole wider "
                          "than a hemisphere): not a hole the front can close"
                        : "the advancing front folded over itself (it turns the wrong way round)";
    // The smallest angle first; the others are sorted only when it cannot be taken.
    std::iter_swap(order_.begin(), std::min_element(order_.begin(), order_.end()));
    for (size_t candidate = 0; candidate < order_.size(); ++candidate) {
      if (candidate == 1) std::sort(order_.begin() + 1, order_.end());
      const Corner corner(F_, fronts_.back(), order_[candidate].second);
      const Step s = chooseStep(corner, order_[candidate].first, F_.patch.meanEdgeLength, options_);
      if (s.op == Op::None) continue;  // nothing valid here: try the next smallest angle
      applyStep(F_, fronts_, corner, s);
      return {};
    }
    return "no front vertex can be advanced without repeating an edge or crossing the front";
  }

  Front& F_;
  const HoleFillOptions& options_;
  int n0_ = 0;
  long maxSteps_ = 0, maxNewVertices_ = 0;
  std::vector<std::vector<int>> fronts_;
  std::unordered_map<int, CachedAngle> angleCache_;
  std::vector<std::pair<double, int>> order_;
  long step_ = 0;
};

// Copies the front's new vertices, their normals and its triangles into the patch.
void storeFront(const Front& F, HolePatch& patch) {
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
}

}  // namespace

HolePatch advancingFront(const PreparedMesh& prepared, const BoundaryLoop& loop, const HoleFillOptions& options) {
  HolePatch patch;
  patch.loop = loop;
  patch.baseId = prepared.mesh().vertexCount();
  if (loop.size() < 3) {
    patch.failure = "a boundary loop of fewer than 3 vertices";
    return patch;
  }
  Front F{prepared, patch, {}, {}, {}, {}};
  measureLoop(F, loop);
  FrontAdvance advance(F, options);
  advance.run();
  patch.closed = advance.closed();
  patch.frontSteps = static_cast<int>(advance.steps());
  storeFront(F, patch);
  return patch;
}

}  // namespace hermite
