#include "scene/hole_fill_stages.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/base/errors.h"
#include "core/shapes/mesh_shapes.h"
#include "io/mesh_file.h"

namespace hermite {

std::string_view holeFillStageName(HoleFillStage s) { return nameIn<HoleFillStage>(kHoleFillStageNames, s); }

const std::vector<std::pair<std::string, std::string>>& holeFillPresets() {
  static const std::vector<std::pair<std::string, std::string>> p{
      {"torus", "a torus mesh with three holes, one on the inner (saddle) side"},
      {"sphere", "a sphere mesh with two holes of different sizes"},
  };
  return p;
}

TriMesh holeFillPresetMesh(const std::string& name) {
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
  for (const auto& [n, _] : holeFillPresets()) names += (names.empty() ? "" : ", ") + n;
  throw InputError("holefill.preset: unknown preset '" + name + "' (expected one of: " + names + ")");
}

HoleFillStages runHoleFillStages(const HoleFillSpec& spec, const std::function<bool(double)>& progress) {
  const auto t0 = std::chrono::steady_clock::now();
  HoleFillStages out;
  MeshRepairReport repair;
  out.input = repairMesh(spec.mesh.empty() ? holeFillPresetMesh(spec.preset)
                                           : loadMesh(spec.resolvedMesh.empty() ? spec.mesh : spec.resolvedMesh),
                         repair);
  out.repairMessages = repair.messages;
  HoleFillOptions options;
  options.rings = spec.rings;
  options.implicit = spec.implicit;
  const PreparedMesh prepared(out.input);
  const std::vector<BoundaryLoop> loops = detectHoles(out.input);
  out.holes.resize(loops.size());
  std::vector<const HolePatch*> patches;
  double reached = 0;  // the fraction last reported
  for (std::size_t h = 0; h < loops.size(); ++h) {
    HoleFillStageHole& hole = out.holes[h];
    hole.loop = loops[h];
    if (h > 0 && out.holes[h - 1].cancelled) {
      hole.reason = "cancelled";
      hole.cancelled = true;
      continue;
    }
    if (progress)  // never backwards: a hole's retry starts its stages again
      options.progress = [&](double f) { return progress(reached = std::max(reached, (double(h) + f) / double(loops.size()))); };
    static_cast<HoleOutcome&>(hole) = fillHole(prepared, loops[h], options, spec.stage, "hole " + std::to_string(h));
    out.unconverged += hole.unconverged;
    out.maxAbsF = std::max(out.maxAbsF, hole.maxAbsF);
    if (hole.filled) {
      patches.push_back(&hole.patch);
      out.trianglesAdded += int(hole.patch.triangles.cols());
    }
  }
  // The combined mesh: the input, then each filled patch's new vertices.
  out.result = appendPatches(out.input, patches);
  out.result.normals.resize(3, 0);
  out.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace hermite
