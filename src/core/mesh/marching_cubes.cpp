// Marching cubes with per-face asymptotic decider and per-cube polygon chaining (marching.h).

#include "core/mesh/marching_cubes.h"

#include <array>
#include <chrono>
#include <cstdint>
#include <vector>

#include "core/mesh/marching_grid.h"

namespace hermite {

namespace {

// Corner c of a cube is at offset (c & 1, (c >> 1) & 1, (c >> 2) & 1) cells. A cube edge is named
// by its lower corner and axis: local id = 3 · corner + axis (24 slots, 12 used).
struct CubeTables {
  // Face f: its four corners counter-clockwise about the outward face normal.
  std::array<std::array<int, 4>, 6> faceCorners{};
  // Whether two local edges lie on a common face of the cube.
  std::array<std::array<bool, 24>, 24> shareFace{};

  CubeTables() {
    int f = 0;
    for (int a = 0; a < 3; ++a) {
      const int u = (a + 1) % 3, w = (a + 2) % 3;  // e_u × e_w = e_a
      for (int side = 0; side < 2; ++side, ++f) {
        // (u, w) offsets counter-clockwise about +e_a; reversed for the face whose normal is −e_a.
        const int uw[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
        for (int i = 0; i < 4; ++i) {
          const int j = side ? i : (4 - i) % 4;
          faceCorners[f][i] = (side << a) | (uw[j][0] << u) | (uw[j][1] << w);
        }
        for (int i = 0; i < 4; ++i)
          for (int k = 0; k < 4; ++k)
            shareFace[faceEdge(f, i)][faceEdge(f, k)] = true;
      }
    }
  }
  // Local id of the edge from the face's corner i to corner i + 1.
  int faceEdge(int f, int i) const { return edgeBetween(faceCorners[f][i], faceCorners[f][(i + 1) % 4]); }
  static int edgeBetween(int c0, int c1) {
    const int diff = c0 ^ c1;
    const int axis = diff == 1 ? 0 : diff == 2 ? 1 : 2;
    return 3 * (c0 & c1) + axis;
  }
};

const CubeTables& tables() {
  static const CubeTables t;
  return t;
}

// Triangles of one layer of cubes: vertex ids ≥ 0 are edge vertices; −1 − i is the centre of
// centres[i] (the polygon's edge vertices).
struct LayerOutput {
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::vector<int>> centres;
};

void marchCube(const detail::MarchingGrid<3>& g, std::int64_t origin, LayerOutput& out) {
  const CubeTables& T = tables();
  std::array<double, 8> v;
  int insideMask = 0;
  for (int c = 0; c < 8; ++c) {
    const std::int64_t idx = origin + (c & 1) * g.stride[0] + ((c >> 1) & 1) * g.stride[1] + ((c >> 2) & 1) * g.stride[2];
    if (!g.isValid(idx)) return;  // no data at a corner: no geometry in the cube
    v[c] = g.values[idx];
    if (v[c] < 0) insideMask |= 1 << c;
  }
  if (insideMask == 0 || insideMask == 255) return;
  auto in = [&](int c) { return (insideMask >> c) & 1; };

  // Directed face segments: next[e] = the edge the contour goes to from edge e. On a face walked
  // counter-clockwise about its outward normal, a crossing is A (inside → outside) or B
  // (outside → inside); each segment runs from a B to an A, which orients the polygon so its fan
  // triangles are counter-clockwise seen from outside (+∇f).
  std::array<int, 24> next;
  next.fill(-1);
  for (int f = 0; f < 6; ++f) {
    const std::array<int, 4>& fc = T.faceCorners[f];
    int edges[4], isA[4], n = 0;
    for (int i = 0; i < 4; ++i)
      if (in(fc[i]) != in(fc[(i + 1) % 4])) {
        edges[n] = T.faceEdge(f, i);
        isA[n++] = in(fc[i]);
      }
    if (n == 2) {
      if (isA[0]) next[edges[1]] = edges[0];
      else next[edges[0]] = edges[1];
    } else if (n == 4) {
      // Asymptotic decider: the bilinear interpolant's value at its saddle. The denominator is
      // non-zero: the diagonal pairs have opposite signs (one pair < 0, the other ≥ 0).
      const double saddle = (v[fc[0]] * v[fc[2]] - v[fc[1]] * v[fc[3]]) / (v[fc[0]] + v[fc[2]] - v[fc[1]] - v[fc[3]]);
      const bool outsideConnected = saddle >= 0;  // then each inside corner is cut off alone
      for (int i = 0; i < 4; ++i) {
        const int j = (i + 1) % 4;
        if (outsideConnected && !isA[i]) next[edges[i]] = edges[j];  // B, then the A leaving the inside corner
        if (!outsideConnected && isA[i]) next[edges[j]] = edges[i];  // A, then the B leaving the outside corner
      }
    }
  }

  std::array<bool, 24> seen{};
  for (int start = 0; start < 24; ++start) {
    if (next[start] < 0 || seen[start]) continue;
    int loop[12], n = 0;
    for (int e = start; !seen[e] && n < 12; e = next[e]) {
      seen[e] = true;
      loop[n++] = e;
    }
    const std::int64_t corner0 = origin;
    auto globalVertex = [&](int local) {
      const int c = local / 3, axis = local % 3;
      const std::int64_t idx = corner0 + (c & 1) * g.stride[0] + ((c >> 1) & 1) * g.stride[1] + ((c >> 2) & 1) * g.stride[2];
      return g.vertexOn(idx, axis);
    };
    int ids[12];
    for (int i = 0; i < n; ++i) ids[i] = globalVertex(loop[i]);
    if (n == 3) {
      out.triangles.push_back({ids[0], ids[1], ids[2]});
      continue;
    }
    // A fan from loop[s] whose diagonals never lie on a cube face.
    int fanStart = -1;
    for (int s = 0; s < n && fanStart < 0; ++s) {
      bool ok = true;
      for (int j = 2; j <= n - 2 && ok; ++j) ok = !T.shareFace[loop[s]][loop[(s + j) % n]];
      if (ok) fanStart = s;
    }
    if (fanStart >= 0) {
      for (int j = 1; j <= n - 2; ++j)
        out.triangles.push_back({ids[fanStart], ids[(fanStart + j) % n], ids[(fanStart + j + 1) % n]});
    } else {
      const int centre = -1 - static_cast<int>(out.centres.size());
      out.centres.emplace_back(ids, ids + n);
      for (int i = 0; i < n; ++i) out.triangles.push_back({centre, ids[i], ids[(i + 1) % n]});
    }
  }
}

// Removes vertices no triangle uses (edge vertices whose cubes all touch a no-data point),
// renumbering the triangles; keeps the order of the rest.
void dropUnusedVertices(TriMesh& mesh) {
  std::vector<int> id(static_cast<size_t>(mesh.vertexCount()), -1);
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) id[static_cast<size_t>(mesh.triangles(k, t))] = 0;
  int kept = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    if (id[static_cast<size_t>(v)] < 0) continue;
    id[static_cast<size_t>(v)] = kept;
    mesh.vertices.col(kept) = mesh.vertices.col(v);
    if (mesh.hasNormals()) mesh.normals.col(kept) = mesh.normals.col(v);
    ++kept;
  }
  const bool normals = mesh.hasNormals();
  mesh.vertices.conservativeResize(3, kept);
  if (normals) mesh.normals.conservativeResize(3, kept);
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) mesh.triangles(k, t) = id[static_cast<size_t>(mesh.triangles(k, t))];
}

}  // namespace

TriMesh marchingCubes(const ImplicitField<3>& field, const Box<3>& box, const MarchingOptions& options,
                      MarchingReport* report) {
  const auto t0 = std::chrono::steady_clock::now();
  detail::MarchingGrid<3> g = detail::sampleGrid<3>(field, box, options, report);
  detail::placeEdgeVertices<3>(g, field, options, report);

  const int layers = g.n[2];
  std::vector<LayerOutput> out(static_cast<size_t>(layers));
#pragma omp parallel for schedule(dynamic, 1)
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < g.n[1]; ++j)
      for (int i = 0; i < g.n[0]; ++i) marchCube(g, i + g.stride[1] * j + g.stride[2] * k, out[static_cast<size_t>(k)]);

  const int V = static_cast<int>(g.edgeKeys.size());
  size_t nCentres = 0, nTriangles = 0;
  for (const LayerOutput& o : out) {
    nCentres += o.centres.size();
    nTriangles += o.triangles.size();
  }
  TriMesh mesh;
  mesh.vertices.resize(3, V + static_cast<Eigen::Index>(nCentres));
  mesh.vertices.leftCols(V) = g.vertices;
  mesh.triangles.resize(3, static_cast<Eigen::Index>(nTriangles));
  int centreBase = V;
  Eigen::Index t = 0;
  for (const LayerOutput& o : out) {
    for (size_t c = 0; c < o.centres.size(); ++c) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int id : o.centres[c]) x += g.vertices.col(id);
      mesh.vertices.col(centreBase + static_cast<int>(c)) = x / static_cast<double>(o.centres[c].size());
    }
    for (const std::array<int, 3>& tri : o.triangles) {
      for (int k = 0; k < 3; ++k) mesh.triangles(k, t) = tri[k] >= 0 ? tri[k] : centreBase - 1 - tri[k];
      ++t;
    }
    centreBase += static_cast<int>(o.centres.size());
  }

  // Normals: ∇f / ‖∇f‖ (centres evaluated here), the area-weighted mesh normal where ∇f vanishes.
  mesh.normals.resize(3, mesh.vertexCount());
  mesh.normals.leftCols(V) = g.gradients;
  if (nCentres > 0) {
    Eigen::VectorXd f;
    Points<3> G;
    field.evaluateBatch(mesh.vertices.rightCols(static_cast<Eigen::Index>(nCentres)), f, &G);
    mesh.normals.rightCols(static_cast<Eigen::Index>(nCentres)) = G;
  }
  const Eigen::Matrix3Xd fallback = vertexNormals(mesh);
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    const double len = mesh.normals.col(v).norm();
    if (len > 1e-300 && std::isfinite(len)) mesh.normals.col(v) /= len;
    else mesh.normals.col(v) = fallback.col(v);
  }
  if (!g.valid.empty()) dropUnusedVertices(mesh);
  if (report) report->totalMs = msSince(t0);
  return mesh;
}

}  // namespace hermite
