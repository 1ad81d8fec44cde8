// Duplicate faces and orientation (mesh_repair.h).

#include "core/mesh/mesh_repair.h"

#include <algorithm>
#include <array>
#include <unordered_map>

namespace hermite {

namespace {

// Triangles with a repeated vertex set after the first are dropped (order kept).
Eigen::Matrix3Xi withoutDuplicates(const Eigen::Matrix3Xi& triangles, int& dropped) {
  std::vector<std::pair<std::array<int, 3>, Eigen::Index>> sorted(std::size_t(triangles.cols()));
  for (Eigen::Index t = 0; t < triangles.cols(); ++t) {
    std::array<int, 3> v{triangles(0, t), triangles(1, t), triangles(2, t)};
    std::sort(v.begin(), v.end());
    sorted[std::size_t(t)] = {v, t};
  }
  std::sort(sorted.begin(), sorted.end());
  std::vector<char> keep(std::size_t(triangles.cols()), 1);
  for (std::size_t k = 1; k < sorted.size(); ++k)
    if (sorted[k].first == sorted[k - 1].first) keep[std::size_t(sorted[k].second)] = 0, ++dropped;
  Eigen::Matrix3Xi out(3, triangles.cols() - dropped);
  for (Eigen::Index t = 0, k = 0; t < triangles.cols(); ++t)
    if (keep[std::size_t(t)]) out.col(k++) = triangles.col(t);
  return out;
}

// Undirected edge → the triangles using it.
std::unordered_map<std::uint64_t, std::vector<int>> edgeTriangles(const Eigen::Matrix3Xi& triangles) {
  std::unordered_map<std::uint64_t, std::vector<int>> edges;
  for (Eigen::Index t = 0; t < triangles.cols(); ++t)
    for (int c = 0; c < 3; ++c) edges[edgeKey(triangles(c, t), triangles((c + 1) % 3, t))].push_back(int(t));
  return edges;
}

bool traverses(const Eigen::Matrix3Xi& triangles, int t, int a, int b) {
  for (int c = 0; c < 3; ++c)
    if (triangles(c, t) == a && triangles((c + 1) % 3, t) == b) return true;
  return false;
}

// Orients each component by a breadth-first walk across two-triangle edges; `flip[t]` is whether
// triangle t must turn. Returns the number of non-orientable components.
int orient(const Eigen::Matrix3Xi& triangles, const std::unordered_map<std::uint64_t, std::vector<int>>& edges,
           std::vector<char>& flip) {
  const int T = int(triangles.cols());
  std::vector<int> component(std::size_t(T), -1);
  flip.assign(std::size_t(T), 0);
  int nonOrientable = 0;
  for (int seed = 0, id = 0; seed < T; ++seed) {
    if (component[seed] >= 0) continue;
    std::vector<int> members{seed}, queue{seed};
    component[seed] = id;
    bool orientable = true;
    while (!queue.empty()) {
      const int t = queue.back();
      queue.pop_back();
      for (int c = 0; c < 3; ++c) {
        int a = triangles(c, t), b = triangles((c + 1) % 3, t);
        if (flip[t]) std::swap(a, b);  // t's edge as t will traverse it
        const std::vector<int>& around = edges.at(edgeKey(a, b));
        if (around.size() != 2) continue;
        const int u = around[0] == t ? around[1] : around[0];
        const bool needsFlip = traverses(triangles, u, a, b);  // u must traverse b → a
        if (component[u] < 0) {
          component[u] = id;
          flip[u] = needsFlip;
          members.push_back(u);
          queue.push_back(u);
        } else if (bool(flip[u]) != needsFlip) {
          orientable = false;
        }
      }
    }
    int flipped = 0;
    for (int t : members) flipped += flip[t];
    if (!orientable) {
      ++nonOrientable;
      for (int t : members) flip[t] = 0;  // no orientation is right: leave it as it was
    } else if (2 * flipped > int(members.size())) {
      for (int t : members) flip[t] = !flip[t];  // the majority's way
    }
    ++id;
  }
  return nonOrientable;
}

// Triangles renumbered to the first vertex at each position; collapsed ones dropped.
Eigen::Matrix3Xi welded(const TriMesh& mesh, int& weldedVertices, int& collapsed) {
  const std::vector<int> first = coincidentVertexRoots(mesh);
  for (int v = 0; v < mesh.vertexCount(); ++v) weldedVertices += first[std::size_t(v)] != v;
  std::vector<Eigen::Index> kept;
  Eigen::Matrix3Xi triangles(3, mesh.triangles.cols());
  for (Eigen::Index t = 0; t < mesh.triangles.cols(); ++t) {
    for (int c = 0; c < 3; ++c) triangles(c, t) = first[std::size_t(mesh.triangles(c, t))];
    if (triangles(0, t) != triangles(1, t) && triangles(1, t) != triangles(2, t) && triangles(0, t) != triangles(2, t))
      kept.push_back(t);
  }
  collapsed = int(triangles.cols()) - int(kept.size());
  Eigen::Matrix3Xi out(3, Eigen::Index(kept.size()));
  for (std::size_t k = 0; k < kept.size(); ++k) out.col(Eigen::Index(k)) = triangles.col(kept[k]);
  return out;
}

}  // namespace

TriMesh repairMesh(const TriMesh& mesh, MeshRepairReport& report) {
  TriMesh out = mesh;
  out.triangles = welded(mesh, report.weldedVertices, report.collapsedFaces);
  out.triangles = withoutDuplicates(out.triangles, report.duplicateFaces);
  const auto edges = edgeTriangles(out.triangles);
  for (const auto& [key, around] : edges) report.nonManifoldEdges += around.size() > 2;
  std::vector<char> flip;
  report.nonOrientableComponents = orient(out.triangles, edges, flip);
  for (Eigen::Index t = 0; t < out.triangles.cols(); ++t)
    if (flip[std::size_t(t)]) {
      std::swap(out.triangles(1, t), out.triangles(2, t));
      ++report.reorientedFaces;
    }
  if (report.weldedVertices > 0)
    report.messages.push_back(std::to_string(report.weldedVertices) +
                              " vertices at the exact position of another welded to it" +
                              (report.collapsedFaces > 0 ? " (" + std::to_string(report.collapsedFaces) +
                                                               " triangles collapsed and dropped)"
                                                         : std::string()));
  if (report.duplicateFaces > 0)
    report.messages.push_back(std::to_string(report.duplicateFaces) + " duplicate faces dropped");
  if (report.reorientedFaces > 0)
    report.messages.push_back(std::to_string(report.reorientedFaces) +
                              " faces turned to agree with the orientation of their neighbours");
  if (report.nonManifoldEdges > 0)
    report.messages.push_back(std::to_string(report.nonManifoldEdges) +
                              " non-manifold edges (three or more triangles): holes next to them may be missed");
  if (report.nonOrientableComponents > 0)
    report.messages.push_back(std::to_string(report.nonOrientableComponents) +
                              " non-orientable components (a Möbius strip?): left as they are");
  return out;
}

}  // namespace hermite
