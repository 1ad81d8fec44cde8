#include "core/mesh/tri_mesh.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <utility>

#include <Eigen/Geometry>

#include "core/base/radix_sort.h"
#include "core/points/lexicographic_order.h"

namespace hermite {

namespace {

// Directed edge (a → b) as one sortable key.
std::uint64_t directedKey(int a, int b) {
  return (std::uint64_t(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}
int keyFrom(std::uint64_t k) { return static_cast<int>(k >> 32); }
int keyTo(std::uint64_t k) { return static_cast<int>(k & 0xffffffffu); }

// Undirected edges with their use counts, sorted by key.
std::vector<std::pair<std::uint64_t, int>> undirectedEdgeCounts(const TriMesh& mesh) {
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * static_cast<size_t>(mesh.triangleCount()));
  for (int t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) keys.push_back(edgeKey(mesh.triangles(k, t), mesh.triangles((k + 1) % 3, t)));
  radixSort(keys);
  std::vector<std::pair<std::uint64_t, int>> out;
  for (size_t i = 0; i < keys.size();) {
    size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    out.emplace_back(keys[i], static_cast<int>(j - i));
    i = j;
  }
  return out;
}

int findRoot(std::vector<int>& parent, int x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

// The boundary edges as directed keys, sorted (grouped by source vertex): one sort of the
// half-edges by undirected edge (the low bit keeps the direction); an edge alone in its group is
// a boundary edge, directed as its one triangle traverses it.
std::vector<std::uint64_t> boundaryEdges(const TriMesh& mesh) {
  std::vector<std::uint64_t> halfEdges;
  halfEdges.reserve(3 * static_cast<size_t>(mesh.triangleCount()));
  for (int t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.triangles(k, t), b = mesh.triangles((k + 1) % 3, t);
      halfEdges.push_back((edgeKey(a, b) << 1) | (a > b ? 1u : 0u));
    }
  std::sort(halfEdges.begin(), halfEdges.end());
  std::vector<std::uint64_t> boundary;
  for (size_t i = 0; i < halfEdges.size();) {
    size_t j = i + 1;
    while (j < halfEdges.size() && (halfEdges[j] >> 1) == (halfEdges[i] >> 1)) ++j;
    if (j == i + 1) {
      const std::uint64_t key = halfEdges[i] >> 1;
      const int lo = keyFrom(key), hi = keyTo(key);
      boundary.push_back(halfEdges[i] & 1 ? directedKey(hi, lo) : directedKey(lo, hi));
    }
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());
  return boundary;
}

}  // namespace

std::vector<BoundaryLoop> boundaryLoops(const TriMesh& mesh) {
  const std::vector<std::uint64_t> boundary = boundaryEdges(mesh);
  std::vector<char> used(boundary.size(), 0);
  // First boundary edge leaving v not used yet, or -1.
  auto nextUnused = [&](int v) -> int {
    auto it = std::lower_bound(boundary.begin(), boundary.end(), directedKey(v, 0));
    for (; it != boundary.end() && keyFrom(*it) == v; ++it) {
      const size_t i = static_cast<size_t>(it - boundary.begin());
      if (!used[i]) return static_cast<int>(i);
    }
    return -1;
  };

  std::vector<BoundaryLoop> loops;
  std::vector<int> posOf(static_cast<size_t>(mesh.vertexCount()), -1);  // position on the current path
  std::vector<int> path;
  for (size_t e0 = 0; e0 < boundary.size(); ++e0) {
    if (used[e0]) continue;
    used[e0] = 1;
    path.assign(1, keyFrom(boundary[e0]));
    posOf[path[0]] = 0;
    int cur = keyTo(boundary[e0]);
    for (;;) {
      if (posOf[cur] >= 0) {
        // Back on the path: the part from cur's first visit is a simple loop.
        const int p = posOf[cur];
        BoundaryLoop loop(path.begin() + p, path.end());
        for (int v : loop) posOf[v] = -1;
        path.resize(static_cast<size_t>(p));
        if (loop.size() >= 3) loops.push_back(std::move(loop));
      }
      posOf[cur] = static_cast<int>(path.size());
      path.push_back(cur);
      const int e = nextUnused(cur);
      if (e < 0) break;  // an open chain (inconsistent orientation): not a loop
      used[static_cast<size_t>(e)] = 1;
      cur = keyTo(boundary[static_cast<size_t>(e)]);
    }
    for (int v : path) posOf[v] = -1;
  }
  return loops;
}

std::vector<int> triangleComponents(const TriMesh& mesh, int* count, std::vector<char>* open) {
  const int T = mesh.triangleCount();
  std::vector<std::pair<std::uint64_t, int>> edgeTri;
  edgeTri.reserve(3 * static_cast<size_t>(T));
  for (int t = 0; t < T; ++t)
    for (int k = 0; k < 3; ++k) edgeTri.emplace_back(edgeKey(mesh.triangles(k, t), mesh.triangles((k + 1) % 3, t)), t);
  radixSort(edgeTri);  // (edge, triangle): a strict total order
  std::vector<int> parent(static_cast<size_t>(T));
  std::iota(parent.begin(), parent.end(), 0);
  for (size_t i = 1; i < edgeTri.size(); ++i)
    if (edgeTri[i].first == edgeTri[i - 1].first) {
      const int a = findRoot(parent, edgeTri[i].second), b = findRoot(parent, edgeTri[i - 1].second);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<int> label(static_cast<size_t>(T), -1), rootLabel(static_cast<size_t>(T), -1);
  int n = 0;
  for (int t = 0; t < T; ++t) {
    const int r = findRoot(parent, t);
    if (rootLabel[r] < 0) rootLabel[r] = n++;
    label[t] = rootLabel[r];
  }
  if (count) *count = n;
  if (open) {
    open->assign(static_cast<size_t>(n), 0);
    for (size_t i = 0; i < edgeTri.size(); ++i)  // an edge of a single triangle: its component is open
      if ((i == 0 || edgeTri[i].first != edgeTri[i - 1].first) &&
          (i + 1 == edgeTri.size() || edgeTri[i + 1].first != edgeTri[i].first))
        (*open)[static_cast<size_t>(label[static_cast<size_t>(edgeTri[i].second)])] = 1;
  }
  return label;
}

std::vector<int> coincidentVertexRoots(const TriMesh& mesh) {
  return coincidentVertexRoots(mesh, lexicographicOrder<3>(mesh.vertices));
}

std::vector<int> coincidentVertexRoots(const TriMesh& mesh, const std::vector<Eigen::Index>& order) {
  std::vector<int> root(static_cast<std::size_t>(mesh.vertexCount()));
  for (std::size_t k = 0; k < order.size(); ++k) {
    const bool same = k > 0 && mesh.vertices.col(order[k]) == mesh.vertices.col(order[k - 1]);
    root[static_cast<std::size_t>(order[k])] = same ? root[static_cast<std::size_t>(order[k - 1])] : int(order[k]);
  }
  return root;
}

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

std::vector<int> vertexConnectedComponents(const TriMesh& mesh, int* count) {
  std::vector<int> parent(static_cast<size_t>(mesh.vertexCount()));
  for (size_t v = 0; v < parent.size(); ++v) parent[v] = static_cast<int>(v);
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t)
    for (int k = 1; k < 3; ++k) {
      const int a = findRoot(parent, mesh.triangles(0, t)), b = findRoot(parent, mesh.triangles(k, t));
      if (a != b) parent[static_cast<size_t>(std::max(a, b))] = std::min(a, b);
    }
  std::vector<int> label(parent.size(), -1), out(static_cast<size_t>(mesh.triangles.cols()));
  int n = 0;
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t) {
    int& l = label[static_cast<size_t>(findRoot(parent, mesh.triangles(0, t)))];
    if (l < 0) l = n++;
    out[static_cast<size_t>(t)] = l;
  }
  if (count) *count = n;
  return out;
}

int vertexConnectedComponentCount(const TriMesh& mesh) {
  int n = 0;
  vertexConnectedComponents(mesh, &n);
  return n;
}

MeshPieces::MeshPieces(const TriMesh& mesh) {
  int count = 0;
  of = vertexConnectedComponents(mesh, &count);
  size.assign(static_cast<std::size_t>(count), 0);
  for (int c : of) ++size[static_cast<std::size_t>(c)];
  if (count > 0) largest = static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin());
}

std::vector<Box<3>> componentBoxes(const TriMesh& mesh, const std::vector<int>& label, int count) {
  std::vector<Box<3>> boxes(static_cast<std::size_t>(count),
                            Box<3>{Vec<3>::Constant(HUGE_VAL), Vec<3>::Constant(-HUGE_VAL)});
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    Box<3>& b = boxes[static_cast<std::size_t>(label[static_cast<std::size_t>(t)])];
    for (int k = 0; k < 3; ++k) {
      b.lo = b.lo.cwiseMin(mesh.vertices.col(mesh.triangles(k, t)));
      b.hi = b.hi.cwiseMax(mesh.vertices.col(mesh.triangles(k, t)));
    }
  }
  return boxes;
}

int dropComponents(TriMesh& mesh, const std::vector<int>& label, const std::vector<char>& drop) {
  int dropped = 0;
  for (char d : drop) dropped += d != 0;
  if (dropped == 0) return 0;
  Eigen::Index kept = 0;
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t)
    if (!drop[static_cast<size_t>(label[static_cast<size_t>(t)])]) mesh.triangles.col(kept++) = mesh.triangles.col(t);
  mesh.triangles.conservativeResize(3, kept);
  dropUnusedVertices(mesh);
  return dropped;
}

int connectedComponentCount(const TriMesh& mesh) {
  int n = 0;
  triangleComponents(mesh, &n);
  return n;
}

Eigen::Matrix3Xd vertexNormals(const TriMesh& mesh, NormalWeighting weighting) {
  Eigen::Matrix3Xd N = Eigen::Matrix3Xd::Zero(3, mesh.vertexCount());
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const Eigen::Vector3i tri = mesh.triangles.col(t);
    const Eigen::Vector3d p[3] = {mesh.vertices.col(tri[0]), mesh.vertices.col(tri[1]), mesh.vertices.col(tri[2])};
    const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]);  // length = 2 × area
    if (weighting == NormalWeighting::Area) {
      for (int k = 0; k < 3; ++k) N.col(tri[k]) += n;
    } else {
      const double len = n.norm();
      if (!(len > 0)) continue;
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d a = p[(k + 1) % 3] - p[k], b = p[(k + 2) % 3] - p[k];
        const double angle = std::atan2(a.cross(b).norm(), a.dot(b));
        N.col(tri[k]) += angle / len * n;
      }
    }
  }
  for (int v = 0; v < N.cols(); ++v) {
    const double len = N.col(v).norm();
    if (len > 0 && std::isfinite(len)) N.col(v) /= len;
    else N.col(v).setZero();
  }
  return N;
}

MeshCheck checkMesh(const TriMesh& mesh, double degenerateArea, bool countComponents) {
  MeshCheck c;
  if (degenerateArea < 0) {
    const double diag = mesh.vertexCount() > 0
                            ? (mesh.vertices.rowwise().maxCoeff() - mesh.vertices.rowwise().minCoeff()).norm()
                            : 0.0;
    degenerateArea = 1e-12 * diag * diag;
  }
  for (const auto& [key, n] : undirectedEdgeCounts(mesh)) {
    ++c.edgeCount;
    if (n == 1) ++c.boundaryEdges;
    if (n >= 3) ++c.nonManifoldEdges;
  }
  std::vector<std::uint64_t> directed;
  directed.reserve(3 * static_cast<size_t>(mesh.triangleCount()));
  std::vector<char> referenced(static_cast<size_t>(mesh.vertexCount()), 0);
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const Eigen::Vector3i tri = mesh.triangles.col(t);
    for (int k = 0; k < 3; ++k) {
      directed.push_back(directedKey(tri[k], tri[(k + 1) % 3]));
      referenced[tri[k]] = 1;
    }
    const double area2 = (mesh.vertices.col(tri[1]) - mesh.vertices.col(tri[0]))
                             .cross(mesh.vertices.col(tri[2]) - mesh.vertices.col(tri[0]))
                             .norm();
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] || !(0.5 * area2 > degenerateArea))
      ++c.degenerateTriangles;
  }
  radixSort(directed);
  for (size_t i = 1; i < directed.size(); ++i)
    if (directed[i] == directed[i - 1]) ++c.inconsistentEdges;
  const int V = static_cast<int>(std::count(referenced.begin(), referenced.end(), 1));
  c.eulerCharacteristic = V - c.edgeCount + mesh.triangleCount();
  if (countComponents) c.components = connectedComponentCount(mesh);
  return c;
}

int countFlippedTriangles(const TriMesh& mesh, const Eigen::Matrix3Xd& referenceNormals) {
  int flipped = 0;
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const Eigen::Vector3i tri = mesh.triangles.col(t);
    const Eigen::Vector3d n = (mesh.vertices.col(tri[1]) - mesh.vertices.col(tri[0]))
                                  .cross(mesh.vertices.col(tri[2]) - mesh.vertices.col(tri[0]));
    const Eigen::Vector3d ref =
        referenceNormals.col(tri[0]) + referenceNormals.col(tri[1]) + referenceNormals.col(tri[2]);
    if (n.dot(ref) < 0) ++flipped;
  }
  return flipped;
}

double surfaceArea(const TriMesh& mesh) {
  double a = 0;
  for (int t = 0; t < mesh.triangleCount(); ++t) a += triangleArea(mesh, t);
  return a;
}

double signedVolume(const TriMesh& mesh) {
  std::vector<int> all(static_cast<std::size_t>(mesh.triangleCount()));
  std::iota(all.begin(), all.end(), 0);
  return signedVolume(mesh, all);
}

double signedVolume(const TriMesh& mesh, const std::vector<int>& triangles) {
  if (triangles.empty()) return 0;
  const Eigen::Vector3d o = mesh.vertices.col(mesh.triangles(0, triangles[0]));
  double v = 0;
  for (int t : triangles) {
    const Eigen::Vector3d a = mesh.vertices.col(mesh.triangles(0, t)) - o, b = mesh.vertices.col(mesh.triangles(1, t)) - o,
                          c = mesh.vertices.col(mesh.triangles(2, t)) - o;
    v += a.dot(b.cross(c));
  }
  return v / 6.0;
}

}  // namespace hermite
