// The whole hole-filling pipeline (hole_fill.h): every hole through stages 2–5, then the
// patches appended to a copy of the mesh.

#include "core/mesh/hole_fill.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <tuple>

#include "core/base/errors.h"
#include "core/base/threading.h"
#include "core/mesh/min_weight_triangulation.h"
#include "core/mesh/patch_refinement.h"

namespace hermite {

namespace {

constexpr double kMinimumPatchAngle = M_PI / 180.0;  // 1°

// Thrown by a stage's progress callback once options.progress has returned false; fillHole
// catches it and reports the hole as cancelled.
struct HoleFillCancelled : std::runtime_error {
  HoleFillCancelled() : std::runtime_error("cancelled") {}
};

// options.progress mapped to the part [lo, hi] of one hole's work (empty without a callback).
std::function<bool(double)> stageProgress(const HoleFillOptions& options, double lo, double hi) {
  if (!options.progress) return {};
  return [&options, lo, hi](double f) {
    if (!options.progress(lo + (hi - lo) * std::clamp(f, 0.0, 1.0))) throw HoleFillCancelled();
    return true;
  };
}

// A 3-edge loop whose vertices are one triangle of the mesh: that triangle touches nothing.
bool isLoneTriangle(const PreparedMesh& prepared, const BoundaryLoop& loop) {
  if (loop.size() != 3) return false;
  for (const int* t = prepared.trianglesBegin(loop[0]); t != prepared.trianglesEnd(loop[0]); ++t) {
    int shared = 0;
    for (int k = 0; k < 3; ++k)
      for (int v : loop) shared += prepared.mesh().triangles(k, *t) == v;
    if (shared == 3) return true;
  }
  return false;
}

// Stage 2: the advancing front (with its retries) for holes of at most frontMaxEdges edges; the
// minimum-weight triangulation for larger holes and where every front attempt fails.
HolePatch firstPatch(const PreparedMesh& prepared, const BoundaryLoop& loop, const HoleFillOptions& options,
                     std::string& method) {
  std::string frontFailure;
  if (int(loop.size()) <= options.frontMaxEdges) {
    HolePatch patch = advancingFront(prepared, loop, options);
    for (size_t r = 0; r < options.frontRetries.size() && !patch.closed; ++r) {
      HoleFillOptions retry = options;
      std::tie(retry.mergeDistance, retry.clipFrontSize) = options.frontRetries[r];
      patch = advancingFront(prepared, loop, retry);
    }
    method = "front";
    if (patch.closed) return patch;
    frontFailure = patch.failure;
  }
  method = "min-weight";
  HolePatch patch = minWeightPatch(prepared, loop, stageProgress(options, 0.0, 0.4));
  if (!patch.closed && !frontFailure.empty())
    patch.failure = "the advancing front failed (" + frontFailure + "), and " + patch.failure;
  return patch;
}

// The smallest angle of patch triangle t, radians.
double triangleSmallestAngle(const PreparedMesh& prepared, const HolePatch& patch, Eigen::Index t) {
  const auto position = [&](int id) -> Vec<3> {
    return id < patch.baseId ? Vec<3>(prepared.mesh().vertices.col(id)) : Vec<3>(patch.vertices.col(id - patch.baseId));
  };
  double smallest = M_PI;
  for (int c = 0; c < 3; ++c) {
    const Vec<3> u = position(patch.triangles((c + 1) % 3, t)) - position(patch.triangles(c, t));
    const Vec<3> v = position(patch.triangles((c + 2) % 3, t)) - position(patch.triangles(c, t));
    const double nu = u.norm(), nv = v.norm();
    smallest = std::min(smallest, nu > 0 && nv > 0 ? std::acos(std::clamp(u.dot(v) / (nu * nv), -1.0, 1.0)) : 0.0);
  }
  return smallest;
}

// The smallest angle of the patch's triangles, radians.
double smallestPatchAngle(const PreparedMesh& prepared, const HolePatch& patch) {
  double smallest = M_PI;
  for (Eigen::Index t = 0; t < patch.triangles.cols(); ++t)
    smallest = std::min(smallest, triangleSmallestAngle(prepared, patch, t));
  return smallest;
}

// The patch's own vertices (0-based) in triangles with an angle below 1°.
std::vector<int> verticesOfSlivers(const PreparedMesh& prepared, const HolePatch& patch) {
  std::vector<int> out;
  for (Eigen::Index t = 0; t < patch.triangles.cols(); ++t) {
    if (triangleSmallestAngle(prepared, patch, t) >= kMinimumPatchAngle) continue;
    for (int c = 0; c < 3; ++c)
      if (patch.triangles(c, t) >= patch.baseId) out.push_back(patch.triangles(c, t) - patch.baseId);
  }
  return out;
}

// Stages 3–5 on a closed first patch, as the options and `last` enable them.
void fairFitProject(const PreparedMesh& prepared, const HoleFillOptions& options, HoleFillStage last,
                    const std::string& name, HolePatch& patch, HoleOutcome& out) {
  const std::function<bool(double)> report = stageProgress(options, 0.4, 1.0);
  if (report) report(0.0);
  if (options.fair && last >= HoleFillStage::Fair) patch = fairPatch(prepared, patch);
  out.unprojected = patch.vertices;
  if (!options.fitAndProject || last < HoleFillStage::Fit || patch.vertices.cols() == 0) return;
  if (patch.rimFold > 0) {  // the surface around a thin wedge continues into the mesh itself
    out.notes.push_back(name + ": closes a thin wedge (" + std::to_string(int(patch.rimFold * 180 / M_PI)) +
                        "° at the rim); the faired patch is kept, not projected onto the implicit");
    return;
  }
  if (report) report(0.2);
  try {
    const HoleImplicit implicit = fitHoleImplicit(prepared, patch, options);
    out.ringPoints = implicit.points;
    out.ringNormals = implicit.normals;
    if (last < HoleFillStage::Project) return;
    HoleFillOptions projection = options;
    projection.progress = stageProgress(options, 0.5, 1.0);
    ProjectionResult projected = projectPatch(prepared, patch, *implicit.field, projection);
    if (projected.cancelled) throw HoleFillCancelled();
    out.unconverged = projected.unconverged;
    out.maxAbsF = projected.maxAbsF;
    if (projected.unconverged > 0)
      out.notes.push_back(name + ": " + std::to_string(projected.unconverged) +
                          " vertices did not converge onto the implicit (left faired)");
    patch = std::move(projected.patch);
  } catch (const NumericalError& e) {
    out.notes.push_back(name + ": implicit fit failed (" + e.what() + "); the faired patch is kept");
  }
}

// Stages 3–5, then angle-improving flips where a triangle has an angle below 1° (a sharp fold, a
// collinear run of boundary vertices). Returns the patch's smallest angle.
double finishPatch(const PreparedMesh& prepared, const HoleFillOptions& options, HoleFillStage last,
                   const std::string& name, HolePatch& patch, HoleOutcome& out) {
  fairFitProject(prepared, options, last, name, patch, out);
  if (smallestPatchAngle(prepared, patch) < kMinimumPatchAngle) improvePatchAngles(prepared, patch);
  // Projection can crowd vertices at a crease: those of triangles still below 1° go back to their
  // faired positions, a few times; failing that the whole faired patch is kept.
  for (int round = 0; round < 3 && smallestPatchAngle(prepared, patch) < kMinimumPatchAngle; ++round) {
    int reverted = 0;
    for (int k : verticesOfSlivers(prepared, patch))
      if (patch.vertices.col(k) != out.unprojected.col(k)) patch.vertices.col(k) = out.unprojected.col(k), ++reverted;
    if (reverted == 0) break;
    improvePatchAngles(prepared, patch, 2);
  }
  if (smallestPatchAngle(prepared, patch) < kMinimumPatchAngle && out.unprojected.cols() == patch.vertices.cols() &&
      patch.vertices != out.unprojected) {
    patch.vertices = out.unprojected;
    improvePatchAngles(prepared, patch, 4);
    out.notes.push_back(name + ": projecting onto the implicit crowded vertices into slivers; the faired patch is kept");
  }
  return smallestPatchAngle(prepared, patch);
}

// The whole job's progress from the holes' own: each hole weighs its boundary edges squared (its
// patch grows with its area); a hole's stages report their fraction of it.
class HolesProgress {
 public:
  HolesProgress(const std::vector<BoundaryLoop>& holes, const std::function<bool(double)>& callback)
      : callback_(callback), weight_(holes.size()), done_(holes.size(), 0.0) {
    for (size_t h = 0; h < holes.size(); ++h) total_ += weight_[h] = double(holes[h].size()) * double(holes[h].size());
  }

  // Hole h has done `fraction` of its work; false once the callback has said stop.
  bool report(size_t h, double fraction) {
    const std::lock_guard<std::mutex> lock(mutex_);
    fraction = std::max(fraction, done_[h]);  // a retry starts its stages again: never backwards
    finished_ += weight_[h] * (fraction - done_[h]);
    done_[h] = fraction;
    if (!cancelled && !callback_(std::clamp(finished_ / total_, 0.0, 1.0))) cancelled = true;
    return !cancelled;
  }

  std::atomic<bool> cancelled{false};

 private:
  const std::function<bool(double)>& callback_;
  std::vector<double> weight_, done_;
  double total_ = 0;
  double finished_ = 0;  // Σ weight × done, under mutex_
  std::mutex mutex_;
};

}  // namespace

HoleOutcome fillHole(const PreparedMesh& prepared, const BoundaryLoop& loop, const HoleFillOptions& options,
                     HoleFillStage last, const std::string& name) {
  HoleOutcome out;
  if (last == HoleFillStage::Holes) return out;
  try {
    if (isLoneTriangle(prepared, loop)) {  // its "hole" is its own back side (a triangle soup?)
      out.reason = "it is the boundary of a lone triangle (unwelded vertices?)";
      out.notes.push_back(name + " not filled: " + out.reason);
      return out;
    }
    HolePatch patch = firstPatch(prepared, loop, options, out.method);
    if (!patch.closed) {
      out.reason = patch.failure;
      out.notes.push_back(name + " not filled: " + patch.failure);
      out.patch = std::move(patch);  // the front as far as it got, for display
      return out;
    }
    double smallest = finishPatch(prepared, options, last, name, patch, out);
    if (smallest < kMinimumPatchAngle && out.method == "front") {
      // The front left slivers (it can stack new vertices on one point): start again from the
      // minimum-weight triangulation and keep whichever is better.
      HoleOutcome retry;
      retry.method = "min-weight";
      HolePatch other = minWeightPatch(prepared, loop, stageProgress(options, 0.0, 0.4));
      if (other.closed) {
        const double otherSmallest = finishPatch(prepared, options, last, name, other, retry);
        if (otherSmallest > smallest) smallest = otherSmallest, patch = std::move(other), out = std::move(retry);
      }
    }
    if (smallest < kMinimumPatchAngle)
      out.notes.push_back(name + ": a new triangle has an angle below 1° (" + std::to_string(smallest * 180 / M_PI) + "°)");
    out.patch = std::move(patch);
    out.filled = true;
  } catch (const HoleFillCancelled& e) {
    out = HoleOutcome{};
    out.reason = e.what();
    out.cancelled = true;
  } catch (const std::exception& e) {  // never let an exception leave a caller's parallel loop
    out.reason = e.what();
    out.notes.push_back(name + " not filled: " + e.what());
  }
  return out;
}

std::vector<BoundaryLoop> detectHoles(const TriMesh& mesh) { return boundaryLoops(mesh); }

TriMesh appendPatches(const TriMesh& mesh, const std::vector<const HolePatch*>& patches) {
  TriMesh out;
  Eigen::Index V = mesh.vertices.cols(), T = mesh.triangles.cols();
  for (const HolePatch* p : patches) {
    V += p->vertices.cols();
    T += p->triangles.cols();
  }
  out.vertices.resize(3, V);
  out.triangles.resize(3, T);
  out.vertices.leftCols(mesh.vertices.cols()) = mesh.vertices;
  out.triangles.leftCols(mesh.triangles.cols()) = mesh.triangles;
  Eigen::Index v = mesh.vertices.cols(), t = mesh.triangles.cols();
  for (const HolePatch* p : patches) {
    const int shift = static_cast<int>(v) - p->baseId;
    out.vertices.middleCols(v, p->vertices.cols()) = p->vertices;
    for (Eigen::Index k = 0; k < p->triangles.cols(); ++k, ++t)
      for (int c = 0; c < 3; ++c) {
        const int id = p->triangles(c, k);
        out.triangles(c, t) = id >= p->baseId ? id + shift : id;
      }
    v += p->vertices.cols();
  }
  return out;
}

namespace {

// Every hole filled through to the projection, one per thread, each with one BLAS thread (its
// system is small — 3 × the ring vertices — and threads inside it would only contend).
// `cancelled` is set when the progress report said stop.
std::vector<HoleOutcome> fillEveryHole(const PreparedMesh& prepared, const std::vector<BoundaryLoop>& holes,
                                       const HoleFillOptions& options, bool& cancelled) {
  std::vector<HoleOutcome> perHole(holes.size());
  const int threads = threadCount();
  setBlasThreadCount(1);
  HolesProgress progress(holes, options.progress);
  const auto report = [&progress](size_t h, double fraction) { return progress.report(h, fraction); };
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (size_t h = 0; h < holes.size(); ++h) {
    if (progress.cancelled) {
      perHole[h].reason = "cancelled";
      perHole[h].cancelled = true;
      continue;
    }
    const std::string name = "hole " + std::to_string(h) + " (" + std::to_string(holes[h].size()) +
                             " boundary edges, at vertex " + std::to_string(holes[h][0]) + ")";
    HoleFillOptions own = options;
    if (options.progress) own.progress = [&report, h](double f) { return report(h, f); };
    perHole[h] = fillHole(prepared, holes[h], own, HoleFillStage::Project, name);
    if (options.progress) report(h, 1.0);
  }
  setThreadCount(threads);
  cancelled = progress.cancelled;
  for (const HoleOutcome& o : perHole) cancelled = cancelled || o.cancelled;
  return perHole;
}

// The per-hole rows, notes and figures of `result`; the filled patches, in hole order.
std::vector<const HolePatch*> collectOutcomes(const std::vector<BoundaryLoop>& holes,
                                              std::vector<HoleOutcome>& perHole, HoleFillResult& result) {
  std::vector<const HolePatch*> patches;
  for (size_t h = 0; h < holes.size(); ++h) {
    HoleOutcome& o = perHole[h];
    result.holes.push_back({int(holes[h].size()), o.method, o.filled, o.reason});
    for (std::string& m : o.notes) result.messages.push_back(std::move(m));
    result.unconverged += o.unconverged;
    result.maxAbsF = std::max(result.maxAbsF, o.maxAbsF);
    if (o.filled) {
      patches.push_back(&o.patch);
      result.trianglesAdded += static_cast<int>(o.patch.triangles.cols());
    }
  }
  return patches;
}

}  // namespace

HoleFillResult fillHoles(const TriMesh& input, const HoleFillOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  HoleFillResult result;
  if (options.rings < 1) throw InputError("hole filling: rings must be ≥ 1");
  if (!(options.offsetFraction > 0)) throw InputError("hole filling: the offset fraction must be > 0");
  // Repairing and preparing a large mesh take a while: a chance to stop before and after each.
  const auto stopped = [&options, &result] {
    return result.cancelled = result.cancelled || (options.progress && !options.progress(0.0));
  };
  if (stopped()) return result;
  const TriMesh mesh = repairMesh(input, result.repair);
  result.messages = result.repair.messages;
  if (stopped()) return result;
  const PreparedMesh prepared(mesh);
  if (stopped()) return result;
  const std::vector<BoundaryLoop> holes = detectHoles(mesh);
  result.holesFound = static_cast<int>(holes.size());
  std::vector<HoleOutcome> perHole = fillEveryHole(prepared, holes, options, result.cancelled);
  const std::vector<const HolePatch*> patches = collectOutcomes(holes, perHole, result);
  // The patches' new vertices get consecutive ids after the input's.
  result.mesh = appendPatches(mesh, patches);
  result.holesFilled = static_cast<int>(patches.size());
  if (mesh.hasNormals()) {  // keep the input's normals; the new vertices get area-weighted ones
    const Eigen::Matrix3Xd computed = vertexNormals(result.mesh);
    result.mesh.normals = computed;
    result.mesh.normals.leftCols(mesh.normals.cols()) = mesh.normals;
  }
  result.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace hermite
