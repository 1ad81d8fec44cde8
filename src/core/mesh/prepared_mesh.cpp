#include "core/mesh/prepared_mesh.h"

#include <algorithm>

namespace hermite {

PreparedMesh::PreparedMesh(const TriMesh& mesh) : mesh_(&mesh) {
  const int V = mesh.vertexCount(), T = mesh.triangleCount();
  normals_ = vertexNormals(mesh, NormalWeighting::Area);
  offsets_.assign(static_cast<size_t>(V) + 1, 0);
  for (int t = 0; t < T; ++t)
    for (int k = 0; k < 3; ++k) ++offsets_[static_cast<size_t>(mesh.triangles(k, t)) + 1];
  for (int v = 0; v < V; ++v) offsets_[v + 1] += offsets_[v];
  triangles_.resize(static_cast<size_t>(offsets_[V]));
  std::vector<int> fill(offsets_.begin(), offsets_.end() - 1);
  for (int t = 0; t < T; ++t)
    for (int k = 0; k < 3; ++k) triangles_[static_cast<size_t>(fill[mesh.triangles(k, t)]++)] = t;
}

std::vector<int> PreparedMesh::neighbours(int v) const {
  std::vector<int> out;
  for (const int* t = trianglesBegin(v); t != trianglesEnd(v); ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh_->triangles(k, *t) != v) out.push_back(mesh_->triangles(k, *t));
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace hermite
