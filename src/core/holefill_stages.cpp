#include "core/holefill_stages.h"

#include <chrono>
#include <cmath>
#include <tuple>

#include "core/errors.h"
#include "core/mesh_io.h"
#include "core/mesh_shapes.h"

namespace hermite {

std::string_view holeFillStageName(HoleFillStage s) {
  switch (s) {
    case HoleFillStage::Holes: return "holes";
    case HoleFillStage::Front: return "front";
    case HoleFillStage::Fair: return "fair";
    case HoleFillStage::Fit: return "fit";
    case HoleFillStage::Project: return "project";
  }
  return "project";
}

const std::vector<std::pair<std::string, std::string>>& holefillPresets() {
  static const std::vector<std::pair<std::string, std::string>> p{
      {"torus", "a torus mesh with three holes, one on the inner (saddle) side"},
      {"sphere", "a sphere mesh with two holes of different sizes"},
  };
  return p;
}

TriMesh holefillPresetMesh(const std::string& name) {
  if (name == "torus") {
    TriMesh m = parametricTorusMesh(96, 48, 0.7, 0.3);
    m = cutBall(m, Vec<3>(0.7, 0.0, 0.3), 0.12);          // top
    m = cutBall(m, Vec<3>(0.0, 0.4, 0.0), 0.1);           // inner side: a saddle region (non-convex hole)
    m = cutBall(m, Vec<3>(-0.7 * 0.6, -0.7 * 0.8, -0.3 + 0.02), 0.16);  // bottom, larger
    return m;
  }
  if (name == "sphere") {
    TriMesh m = uvSphereMesh(64, 32);
    m = cutBall(m, Vec<3>(1, 0, 0), 0.25);
    m = cutBall(m, Vec<3>(0, 0.6, 0.8), 0.45);
    return m;
  }
  std::string names;
  for (const auto& [n, _] : holefillPresets()) names += (names.empty() ? "" : ", ") + n;
  throw InputError("holefill.preset: unknown preset '" + name + "' (expected one of: " + names + ")");
}

HolefillStages runHolefillStages(const HolefillSpec& spec) {
  const auto t0 = std::chrono::steady_clock::now();
  HolefillStages out;
  out.input = spec.mesh.empty() ? holefillPresetMesh(spec.preset)
                                : loadMesh(spec.resolvedMesh.empty() ? spec.mesh : spec.resolvedMesh);
  HoleFillOptions options;
  options.rings = spec.rings;
  options.implicit = spec.implicit;
  const PreparedMesh prepared(out.input);
  const std::vector<BoundaryLoop> loops = detectHoles(out.input);
  out.holes.resize(loops.size());
  out.result = out.input;
  for (std::size_t h = 0; h < loops.size(); ++h) {
    HolefillStageHole& hole = out.holes[h];
    hole.loop = loops[h];
    if (spec.stage == HoleFillStage::Holes) continue;
    try {
      HolePatch patch = advancingFront(prepared, loops[h], options);
      for (std::size_t r = 0; r < options.frontRetries.size() && !patch.closed; ++r) {
        HoleFillOptions retry = options;
        std::tie(retry.mergeDistance, retry.clipFrontSize) = options.frontRetries[r];
        patch = advancingFront(prepared, loops[h], retry);
      }
      if (!patch.closed) {
        hole.note = "not closed: " + patch.failure;
        hole.patch = std::move(patch);
        continue;
      }
      if (spec.stage >= HoleFillStage::Fair) patch = fairPatch(prepared, patch);
      if (spec.stage >= HoleFillStage::Fit && patch.vertices.cols() > 0) {
        const HoleImplicit implicit = fitHoleImplicit(prepared, patch, options);
        hole.ringPoints = implicit.points;
        hole.ringNormals = implicit.normals;
        if (spec.stage >= HoleFillStage::Project) {
          ProjectionResult p = projectPatch(prepared, patch, *implicit.field, options);
          out.unconverged += p.unconverged;
          out.maxAbsF = std::max(out.maxAbsF, p.maxAbsF);
          if (p.unconverged > 0) hole.note = std::to_string(p.unconverged) + " vertices did not converge";
          patch = std::move(p.patch);
        }
      }
      hole.patch = std::move(patch);
      hole.filled = true;
    } catch (const std::exception& e) {
      hole.note = std::string("not filled: ") + e.what();
    }
  }
  // The combined mesh: the input, then each filled patch's new vertices (ids shifted).
  for (const HolefillStageHole& hole : out.holes) {
    if (!hole.filled) continue;
    const HolePatch& p = hole.patch;
    const int base = out.result.vertexCount();
    out.result.vertices.conservativeResize(3, base + p.vertices.cols());
    out.result.vertices.rightCols(p.vertices.cols()) = p.vertices;
    const int t0i = out.result.triangleCount();
    out.result.triangles.conservativeResize(3, t0i + p.triangles.cols());
    for (Eigen::Index t = 0; t < p.triangles.cols(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int v = p.triangles(k, t);
        out.result.triangles(k, t0i + t) = v >= p.baseId ? base + (v - p.baseId) : v;
      }
    out.trianglesAdded += int(p.triangles.cols());
  }
  out.result.normals.resize(3, 0);
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace hermite
