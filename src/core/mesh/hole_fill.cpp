// The whole hole-filling pipeline (hole_fill.h): every hole through stages 2–5, then the
// patches appended to a copy of the mesh.

#include "core/mesh/hole_fill.h"

#include <algorithm>
#include <chrono>
#include <exception>
#include <tuple>

#include "core/base/errors.h"
#include "core/base/threading.h"

namespace hermite {

namespace {

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

}  // namespace

HoleOutcome fillHole(const PreparedMesh& prepared, const BoundaryLoop& loop, const HoleFillOptions& options,
                     HoleFillStage last, const std::string& name) {
  HoleOutcome out;
  if (last == HoleFillStage::Holes) return out;
  try {
    if (isLoneTriangle(prepared, loop)) {  // its "hole" is its own back side (a triangle soup?)
      out.notes.push_back(name + " not filled: it is the boundary of a lone triangle (unwelded vertices?)");
      return out;
    }
    HolePatch patch = advancingFront(prepared, loop, options);
    for (size_t r = 0; r < options.frontRetries.size() && !patch.closed; ++r) {
      HoleFillOptions retry = options;
      std::tie(retry.mergeDistance, retry.clipFrontSize) = options.frontRetries[r];
      patch = advancingFront(prepared, loop, retry);
    }
    if (!patch.closed) {
      out.notes.push_back(name + " not filled: " + patch.failure);
      out.patch = std::move(patch);  // the front as far as it got, for display
      return out;
    }
    if (options.fair && last >= HoleFillStage::Fair) patch = fairPatch(prepared, patch);
    if (options.fitAndProject && last >= HoleFillStage::Fit && patch.vertices.cols() > 0) {
      try {
        const HoleImplicit implicit = fitHoleImplicit(prepared, patch, options);
        out.ringPoints = implicit.points;
        out.ringNormals = implicit.normals;
        if (last >= HoleFillStage::Project) {
          ProjectionResult projected = projectPatch(prepared, patch, *implicit.field, options);
          out.unconverged = projected.unconverged;
          out.maxAbsF = projected.maxAbsF;
          if (projected.unconverged > 0)
            out.notes.push_back(name + ": " + std::to_string(projected.unconverged) +
                                " vertices did not converge onto the implicit (left faired)");
          patch = std::move(projected.patch);
        }
      } catch (const NumericalError& e) {
        out.notes.push_back(name + ": implicit fit failed (" + e.what() + "); the faired patch is kept");
      }
    }
    out.patch = std::move(patch);
    out.filled = true;
  } catch (const std::exception& e) {  // never let an exception leave a caller's parallel loop
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

HoleFillResult fillHoles(const TriMesh& mesh, const HoleFillOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  HoleFillResult result;
  if (options.rings < 1) throw InputError("hole filling: rings must be ≥ 1");
  if (!(options.offsetFraction > 0)) throw InputError("hole filling: the offset fraction must be > 0");
  const PreparedMesh prepared(mesh);
  const std::vector<BoundaryLoop> holes = detectHoles(mesh);
  result.holesFound = static_cast<int>(holes.size());

  // Holes are independent: one per thread, each with one BLAS thread (its system is small —
  // 3 × the ring vertices — and threads inside it would only contend).
  std::vector<HoleOutcome> perHole(holes.size());
  const int threads = threadCount();
  setBlasThreadCount(1);
#pragma omp parallel for num_threads(threads) schedule(dynamic, 1)
  for (size_t h = 0; h < holes.size(); ++h) {
    const std::string name = "hole " + std::to_string(h) + " (" + std::to_string(holes[h].size()) +
                             " boundary edges, at vertex " + std::to_string(holes[h][0]) + ")";
    perHole[h] = fillHole(prepared, holes[h], options, HoleFillStage::Project, name);
  }
  setThreadCount(threads);
  std::vector<const HolePatch*> patches;
  for (HoleOutcome& o : perHole) {
    for (std::string& m : o.notes) result.messages.push_back(std::move(m));
    result.unconverged += o.unconverged;
    result.maxAbsF = std::max(result.maxAbsF, o.maxAbsF);
    if (o.filled) {
      patches.push_back(&o.patch);
      result.trianglesAdded += static_cast<int>(o.patch.triangles.cols());
    }
  }
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
