#include "core/holefill_stages.h"

#include <chrono>
#include <cmath>
#include <tuple>

#include "core/errors.h"
#include "core/mesh_io.h"

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

namespace {

// (R + r cos v) cos u, ... on an nu × nv grid, counter-clockwise from outside.
TriMesh torusMesh(int nu, int nv, double R, double r) {
  TriMesh m;
  m.vertices.resize(3, nu * nv);
  m.triangles.resize(3, 2 * nu * nv);
  const auto id = [&](int i, int j) { return (i % nu) * nv + (j % nv); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u = 2 * M_PI * i / nu, v = 2 * M_PI * j / nv;
      m.vertices.col(id(i, j)) =
          Vec<3>((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
      m.triangles.col(2 * id(i, j)) = Eigen::Vector3i(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.triangles.col(2 * id(i, j) + 1) = Eigen::Vector3i(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return m;
}

// A UV sphere of radius 1 (poles as single vertices), counter-clockwise from outside.
TriMesh sphereMesh(int nu, int nv) {
  TriMesh m;
  const int rings = nv - 1;  // latitude rings without the poles
  m.vertices.resize(3, nu * rings + 2);
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < nu; ++i) {
      const double th = M_PI * (j + 1) / nv, ph = 2 * M_PI * i / nu;
      m.vertices.col(j * nu + i) = Vec<3>(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
    }
  const int north = nu * rings, south = north + 1;
  m.vertices.col(north) = Vec<3>(0, 0, 1);
  m.vertices.col(south) = Vec<3>(0, 0, -1);
  std::vector<Eigen::Vector3i> t;
  for (int i = 0; i < nu; ++i) {
    const int a = i, b = (i + 1) % nu;
    t.emplace_back(north, a, b);
    for (int j = 0; j + 1 < rings; ++j) {
      const int p = j * nu + a, q = j * nu + b, p2 = p + nu, q2 = q + nu;
      t.emplace_back(p, p2, q2);
      t.emplace_back(p, q2, q);
    }
    t.emplace_back(south, (rings - 1) * nu + b, (rings - 1) * nu + a);
  }
  m.triangles.resize(3, Eigen::Index(t.size()));
  for (std::size_t k = 0; k < t.size(); ++k) m.triangles.col(Eigen::Index(k)) = t[k];
  return m;
}

// Removes every triangle with a vertex within `radius` of `centre` (vertex ids unchanged).
TriMesh cut(const TriMesh& mesh, const Vec<3>& centre, double radius) {
  std::vector<int> keep;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    bool inside = false;
    for (int k = 0; k < 3; ++k) inside |= (mesh.vertices.col(mesh.triangles(k, t)) - centre).norm() < radius;
    if (!inside) keep.push_back(t);
  }
  TriMesh out = mesh;
  out.triangles.resize(3, Eigen::Index(keep.size()));
  for (std::size_t k = 0; k < keep.size(); ++k) out.triangles.col(Eigen::Index(k)) = mesh.triangles.col(keep[k]);
  return out;
}

}  // namespace

TriMesh holefillPresetMesh(const std::string& name) {
  if (name == "torus") {
    TriMesh m = torusMesh(96, 48, 0.7, 0.3);
    m = cut(m, Vec<3>(0.7, 0.0, 0.3), 0.12);          // top
    m = cut(m, Vec<3>(0.0, 0.4, 0.0), 0.1);           // inner side: a saddle region (non-convex hole)
    m = cut(m, Vec<3>(-0.7 * 0.6, -0.7 * 0.8, -0.3 + 0.02), 0.16);  // bottom, larger
    return m;
  }
  if (name == "sphere") {
    TriMesh m = sphereMesh(64, 32);
    m = cut(m, Vec<3>(1, 0, 0), 0.25);
    m = cut(m, Vec<3>(0, 0.6, 0.8), 0.45);
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
