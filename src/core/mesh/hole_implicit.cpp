// Stages 4–5 of hole filling (hole_fill.h): the implicit around a hole and the Newton projection
// of the patch onto its zero set.

#include "core/mesh/hole_implicit.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numeric>

#include <Eigen/Geometry>

#include "core/base/errors.h"
#include "core/rbf/hrbf.h"
#include "core/rbf/rbf_offset.h"

namespace hermite {

HoleImplicit fitHoleImplicit(const PreparedMesh& prepared, const HolePatch& patch, const HoleFillOptions& options) {
  if (options.rings < 1) throw InputError("hole filling: rings must be ≥ 1");
  if (!(options.offsetFraction > 0)) throw InputError("hole filling: the offset fraction must be > 0");
  // Rings: the boundary, then each ring's original-mesh neighbours not seen yet.
  std::vector<int> ringVertices = patch.loop, frontier = patch.loop;
  std::vector<int> seen = patch.loop;
  std::sort(seen.begin(), seen.end());
  for (int r = 1; r < options.rings; ++r) {
    std::vector<int> next;
    for (int v : frontier)
      for (int u : prepared.neighbours(v))
        if (!std::binary_search(seen.begin(), seen.end(), u)) next.push_back(u);
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    ringVertices.insert(ringVertices.end(), next.begin(), next.end());
    seen.insert(seen.end(), next.begin(), next.end());
    std::sort(seen.begin(), seen.end());
    frontier = std::move(next);
  }
  // Usable samples: a non-zero normal and a position not seen before (unwelded copies).
  std::vector<int> use;
  for (int v : ringVertices)
    if (prepared.normals().col(v).norm() > 0.5) use.push_back(v);
  std::sort(use.begin(), use.end(), [&](int a, int b) {
    const Eigen::Vector3d pa = prepared.mesh().vertices.col(a), pb = prepared.mesh().vertices.col(b);
    return std::lexicographical_compare(pa.data(), pa.data() + 3, pb.data(), pb.data() + 3);
  });
  use.erase(std::unique(use.begin(), use.end(),
                        [&](int a, int b) { return prepared.mesh().vertices.col(a) == prepared.mesh().vertices.col(b); }),
            use.end());
  if (static_cast<int>(use.size()) > options.maxFitSamples) {  // evenly thinned, deterministic
    std::vector<int> thin;
    const double stride = static_cast<double>(use.size()) / options.maxFitSamples;
    for (int i = 0; i < options.maxFitSamples; ++i) thin.push_back(use[static_cast<size_t>(i * stride)]);
    use = std::move(thin);
  }
  if (use.size() < 4) throw NumericalError("hole filling: fewer than 4 usable vertices around the hole to fit");

  HermiteSamples<3> samples;
  samples.points.resize(3, static_cast<Eigen::Index>(use.size()));
  samples.normals.resize(3, static_cast<Eigen::Index>(use.size()));
  for (size_t i = 0; i < use.size(); ++i) {
    samples.points.col(static_cast<Eigen::Index>(i)) = prepared.mesh().vertices.col(use[i]);
    samples.normals.col(static_cast<Eigen::Index>(i)) = prepared.normals().col(use[i]);
  }
  HoleImplicit out;
  out.kind = options.implicit;
  out.points = samples.points;
  out.normals = samples.normals;
  if (options.implicit == HoleImplicitKind::RbfOffset) {
    RbfOffsetOptions o;  // cubic x³ with a linear polynomial: the classic choice
    out.offset = options.offsetFraction * std::max(patch.diameter, 1e-12);
    o.shift = out.offset;
    out.field = std::make_unique<RbfOffsetModel<3>>(fitRbfOffset<3>(samples, o));
  } else {
    out.field = std::make_unique<HrbfModel<3>>(fitHrbf<3>(samples, HrbfOptions{}));
  }
  return out;
}

namespace {

// Columns per batch evaluation between progress reports: about 10 ms of a 3 000-centre field.
constexpr Eigen::Index kEvaluationChunk = 1024;

// f (and ∇f into G when given) at the columns of X, a chunk at a time, reporting `at` between
// chunks. False when the report says stop.
bool evaluateInChunks(const ImplicitField<3>& field, const Eigen::Matrix3Xd& X, Eigen::VectorXd& f, Points<3>* G,
                      const std::function<bool(double)>& progress, double at) {
  const Eigen::Index K = X.cols();
  f.resize(K);
  if (G) G->resize(3, K);
  Eigen::VectorXd fc;
  Points<3> Gc;
  for (Eigen::Index start = 0; start < K; start += kEvaluationChunk) {
    if (progress && !progress(at)) return false;
    const Eigen::Index n = std::min(kEvaluationChunk, K - start);
    field.evaluateBatch(X.middleCols(start, n), fc, G ? &Gc : nullptr);
    f.segment(start, n) = fc;
    if (G) G->middleCols(start, n) = Gc;
  }
  return true;
}

// Three Newton steps for all of the patch's vertices at once (batch evaluation), then every
// vertex of a triangle that `valid` rejects back to its faired position, until none is rejected.
// False when the progress report says stop.
template <class Valid>
bool batchedNewtonStart(const ImplicitField<3>& field, const Eigen::Matrix3Xd& faired, double scale, Valid valid,
                        const std::function<bool(double)>& progress, HolePatch& P) {
  const Eigen::Index K = P.vertices.cols();
  for (int it = 0; it < 3; ++it) {
    Eigen::VectorXd f;
    Points<3> G;
    if (!evaluateInChunks(field, P.vertices, f, &G, progress, 0.0)) return false;
    for (Eigen::Index k = 0; k < K; ++k) {
      const double g2 = G.col(k).squaredNorm();
      if (!std::isfinite(f(k)) || !(g2 > 0) || !std::isfinite(g2)) continue;
      Eigen::Vector3d step = -f(k) / g2 * G.col(k);
      if (step.norm() > 0.5 * scale) step *= 0.5 * scale / step.norm();
      P.vertices.col(k) += step;
    }
  }
  for (bool reverted = true; reverted;) {
    reverted = false;
    for (Eigen::Index t = 0; t < P.triangles.cols(); ++t) {
      if (valid(t)) continue;
      for (int c = 0; c < 3; ++c) {
        const int id = P.triangles(c, t);
        if (id >= P.baseId && P.vertices.col(id - P.baseId) != faired.col(id - P.baseId))
          P.vertices.col(id - P.baseId) = faired.col(id - P.baseId), reverted = true;
      }
    }
  }
  return true;
}

// Patches with at least this many new vertices start with batched Newton steps.
constexpr int kBatchProjectionVertices = 4096;

// The patch's triangles against their orientation before projection: which positions of a new
// vertex keep every triangle around it unflipped and non-degenerate. Reads the patch's current
// vertex positions (the projection moves them).
class PatchOrientation {
 public:
  PatchOrientation(const PreparedMesh& prepared, const HolePatch& P) : prepared_(prepared), P_(P) {
    const Eigen::Index T = P.triangles.cols();
    reference_.resize(static_cast<size_t>(T));
    incident_.resize(static_cast<size_t>(P.vertices.cols()));
    for (Eigen::Index t = 0; t < T; ++t) {
      reference_[static_cast<size_t>(t)] = triangleNormal(t);
      for (int k = 0; k < 3; ++k)
        if (P.triangles(k, t) >= P.baseId) incident_[static_cast<size_t>(P.triangles(k, t) - P.baseId)].push_back(t);
    }
    minArea2_ = 1e-10 * P.meanEdgeLength * P.meanEdgeLength;
  }
  // Triangle t is not degenerate and faces the way it did.
  bool unflipped(Eigen::Index t) const {
    const Eigen::Vector3d n = triangleNormal(t);
    return n.norm() > minArea2_ && n.dot(reference_[static_cast<size_t>(t)]) > 0;
  }
  // Every triangle of new vertex k is unflipped at k's current position.
  bool acceptable(int k) const {
    for (Eigen::Index t : incident_[static_cast<size_t>(k)])
      if (!unflipped(t)) return false;
    return true;
  }

 private:
  Eigen::Vector3d position(int id) const {
    return id >= P_.baseId ? Eigen::Vector3d(P_.vertices.col(id - P_.baseId))
                           : Eigen::Vector3d(prepared_.mesh().vertices.col(id));
  }
  Eigen::Vector3d triangleNormal(Eigen::Index t) const {  // 2 × area times the unit normal
    return (position(P_.triangles(1, t)) - position(P_.triangles(0, t)))
        .cross(position(P_.triangles(2, t)) - position(P_.triangles(0, t)));
  }
  const PreparedMesh& prepared_;
  const HolePatch& P_;
  std::vector<Eigen::Vector3d> reference_;
  std::vector<std::vector<Eigen::Index>> incident_;
  double minArea2_ = 0;
};

enum class VertexProjection { Converged, Blocked, Unfinished };

// Newton steps x ← x − f ∇f/‖∇f‖² for new vertex k, each halved up to four times until k's
// triangles stay acceptable; a step that cannot be made acceptable leaves k where it was.
VertexProjection projectVertex(int k, HolePatch& P, const ImplicitField<3>& field, const PatchOrientation& orientation,
                               double scale, const HoleFillOptions& options) {
  for (int it = 0; it < options.newtonIterations; ++it) {
    const Eigen::Vector3d x = P.vertices.col(k);
    Vec<3> g;
    const double f = field.evaluate(x, &g);
    const double g2 = g.squaredNorm();
    if (!std::isfinite(f) || !(g2 > 0) || !std::isfinite(g2)) return VertexProjection::Unfinished;
    Eigen::Vector3d step = -f / g2 * g;
    if (step.norm() > 0.5 * scale) step *= 0.5 * scale / step.norm();  // a wild step: bounded
    bool accepted = false;
    for (int halving = 0; halving <= 4 && !accepted; ++halving, step *= 0.5) {
      P.vertices.col(k) = x + step;
      accepted = orientation.acceptable(k);
    }
    if (!accepted) {
      P.vertices.col(k) = x;
      return VertexProjection::Blocked;
    }
    if ((P.vertices.col(k) - x).norm() < options.newtonTolerance * scale) return VertexProjection::Converged;
  }
  return VertexProjection::Unfinished;
}

// Gauss–Seidel sweeps: a vertex whose step was blocked by a neighbour not yet projected gets
// another chance once the neighbours have moved. Marks `converged`; false when cancelled.
bool projectionSweeps(HolePatch& P, const ImplicitField<3>& field, const PatchOrientation& orientation, double scale,
                      const HoleFillOptions& options, std::vector<char>& converged) {
  const int K = static_cast<int>(P.vertices.cols());
  for (int sweep = 0; sweep < 3; ++sweep) {
    bool blocked = false;
    for (int k = 0; k < K; ++k) {
      if (options.progress && k % 256 == 0 && !options.progress((sweep + double(k) / K) / 3.0)) return false;
      if (converged[static_cast<size_t>(k)]) continue;
      const VertexProjection outcome = projectVertex(k, P, field, orientation, scale, options);
      converged[static_cast<size_t>(k)] = outcome == VertexProjection::Converged;
      blocked |= outcome == VertexProjection::Blocked;
    }
    if (!blocked) break;
  }
  return true;
}

}  // namespace

ProjectionResult projectPatch(const PreparedMesh& prepared, const HolePatch& patch, const ImplicitField<3>& field,
                              const HoleFillOptions& options) {
  ProjectionResult result;
  result.patch = patch;
  HolePatch& P = result.patch;
  const int K = static_cast<int>(P.vertices.cols());
  const PatchOrientation orientation(prepared, P);
  const double scale = std::max(P.diameter, 1e-300);
  const Eigen::Matrix3Xd faired = P.vertices;
  // Large patches: Newton steps for all vertices at once first (batch evaluation), then every
  // vertex of a triangle they flipped or degenerated back to its faired position; the sweeps
  // below finish from there.
  const auto unflipped = [&](Eigen::Index t) { return orientation.unflipped(t); };
  std::vector<char> converged(static_cast<size_t>(K), 0);
  if ((K >= kBatchProjectionVertices && !batchedNewtonStart(field, faired, scale, unflipped, options.progress, P)) ||
      !projectionSweeps(P, field, orientation, scale, options, converged)) {
    result.cancelled = true;
    return result;
  }
  for (int k = 0; k < K; ++k) {
    if (converged[static_cast<size_t>(k)]) continue;
    ++result.unconverged;
    const Eigen::Vector3d last = P.vertices.col(k);
    P.vertices.col(k) = faired.col(k);  // back to the faired position, unless that would now flip a triangle
    if (!orientation.acceptable(k)) P.vertices.col(k) = last;
  }
  Eigen::VectorXd f;
  if (!evaluateInChunks(field, P.vertices, f, nullptr, options.progress, 1.0)) {
    result.cancelled = true;
    return result;
  }
  for (Eigen::Index k = 0; k < K; ++k) result.maxAbsF = std::max(result.maxAbsF, std::abs(f(k)));
  return result;
}

}  // namespace hermite
