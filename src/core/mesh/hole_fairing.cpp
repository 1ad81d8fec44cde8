// Stage 3 of hole filling (hole_fill.h): least-squares-mesh fairing of a patch.

#include "core/mesh/hole_fairing.h"

#include <algorithm>
#include <unordered_map>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/base/errors.h"

namespace hermite {

HolePatch fairPatch(const PreparedMesh& prepared, const HolePatch& patch) {
  HolePatch out = patch;
  const int K = static_cast<int>(patch.vertices.cols());
  if (K == 0) return out;
  const TriMesh& mesh = prepared.mesh();
  auto isNew = [&](int id) { return id >= patch.baseId; };
  auto position = [&](int id) -> Eigen::Vector3d {
    return isNew(id) ? Eigen::Vector3d(patch.vertices.col(id - patch.baseId)) : Eigen::Vector3d(mesh.vertices.col(id));
  };

  // One-rings: the patch's edges, plus the original mesh's around the boundary vertices.
  std::unordered_map<int, std::vector<int>> ring;
  for (Eigen::Index t = 0; t < patch.triangles.cols(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = patch.triangles(k, t), b = patch.triangles((k + 1) % 3, t);
      ring[a].push_back(b);
      ring[b].push_back(a);
    }
  for (int v : patch.loop) {
    const std::vector<int> nb = prepared.neighbours(v);
    ring[v].insert(ring[v].end(), nb.begin(), nb.end());
  }
  // Rows: every vertex of the patch (new and boundary); the unknowns are the new vertices.
  std::vector<int> rows;
  for (auto& [v, nb] : ring) {
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
    rows.push_back(v);
  }
  std::sort(rows.begin(), rows.end());  // deterministic
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d b = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t r = 0; r < rows.size(); ++r) {
    const int v = rows[r];
    const std::vector<int>& nb = ring[v];
    const double w = 1.0 / static_cast<double>(nb.size());
    // (L x)_v = x_v − mean of the one-ring; known terms go to the right-hand side.
    if (isNew(v)) entries.emplace_back(static_cast<int>(r), v - patch.baseId, 1.0);
    else b.row(static_cast<Eigen::Index>(r)) -= position(v).transpose();
    for (int u : nb) {
      if (isNew(u)) entries.emplace_back(static_cast<int>(r), u - patch.baseId, -w);
      else b.row(static_cast<Eigen::Index>(r)) += w * position(u).transpose();
    }
  }
  Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(rows.size()), K);
  A.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SparseMatrix<double> AtA = A.transpose() * A;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(AtA);
  if (solver.info() != Eigen::Success)
    throw NumericalError("hole fairing: the least-squares normal equations could not be factorised");
  const Eigen::MatrixX3d X = solver.solve(A.transpose() * b);
  if (solver.info() != Eigen::Success || !X.allFinite())
    throw NumericalError("hole fairing: the least-squares solve failed (result not finite)");
  out.vertices = X.transpose();
  return out;
}

}  // namespace hermite
