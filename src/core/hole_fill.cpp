// The whole hole-filling pipeline (hole_fill.h): every hole through stages 2–5, then the
// patches appended to a copy of the mesh.

#include "core/hole_fill.h"

#include <chrono>
#include <exception>
#include <tuple>

#include "core/errors.h"

namespace hermite {

HoleFillResult fillHoles(const TriMesh& mesh, const HoleFillOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  HoleFillResult result;
  const PreparedMesh prepared(mesh);
  const std::vector<BoundaryLoop> holes = detectHoles(mesh);
  result.holesFound = static_cast<int>(holes.size());

  std::vector<HolePatch> patches;
  for (size_t h = 0; h < holes.size(); ++h) {
    const std::string name = "hole " + std::to_string(h) + " (" + std::to_string(holes[h].size()) +
                             " boundary edges, at vertex " + std::to_string(holes[h][0]) + ")";
    HolePatch patch = advancingFront(prepared, holes[h], options);
    for (size_t r = 0; r < options.frontRetries.size() && !patch.closed; ++r) {
      HoleFillOptions retry = options;
      std::tie(retry.mergeDistance, retry.clipFrontSize) = options.frontRetries[r];
      patch = advancingFront(prepared, holes[h], retry);
    }
    if (!patch.closed) {
      result.messages.push_back(name + " not filled: " + patch.failure);
      continue;
    }
    if (options.fair) patch = fairPatch(prepared, patch);
    if (options.fitAndProject && patch.vertices.cols() > 0) {
      try {
        const HoleImplicit implicit = fitHoleImplicit(prepared, patch, options);
        ProjectionResult projected = projectPatch(prepared, patch, *implicit.field, options);
        result.unconverged += projected.unconverged;
        result.maxAbsF = std::max(result.maxAbsF, projected.maxAbsF);
        if (projected.unconverged > 0)
          result.messages.push_back(name + ": " + std::to_string(projected.unconverged) +
                                    " vertices did not converge onto the implicit (left faired)");
        patch = std::move(projected.patch);
      } catch (const NumericalError& e) {
        result.messages.push_back(name + ": implicit fit failed (" + e.what() + "); the faired patch is kept");
      }
    }
    patches.push_back(std::move(patch));
  }

  // Append: the patches' new vertices get consecutive ids after the input's.
  Eigen::Index V = mesh.vertices.cols(), T = mesh.triangles.cols();
  for (const HolePatch& p : patches) {
    V += p.vertices.cols();
    T += p.triangles.cols();
  }
  result.mesh.vertices.resize(3, V);
  result.mesh.triangles.resize(3, T);
  result.mesh.vertices.leftCols(mesh.vertices.cols()) = mesh.vertices;
  result.mesh.triangles.leftCols(mesh.triangles.cols()) = mesh.triangles;
  Eigen::Index v = mesh.vertices.cols(), t = mesh.triangles.cols();
  for (const HolePatch& p : patches) {
    const int shift = static_cast<int>(v) - p.baseId;
    result.mesh.vertices.middleCols(v, p.vertices.cols()) = p.vertices;
    for (Eigen::Index k = 0; k < p.triangles.cols(); ++k, ++t)
      for (int c = 0; c < 3; ++c) {
        const int id = p.triangles(c, k);
        result.mesh.triangles(c, t) = id >= p.baseId ? id + shift : id;
      }
    v += p.vertices.cols();
    result.trianglesAdded += static_cast<int>(p.triangles.cols());
  }
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
