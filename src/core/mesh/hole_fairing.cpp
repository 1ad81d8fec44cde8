// Stage 3 of hole filling (hole_fill.h): least-squares-mesh fairing of a patch.

#include "core/mesh/hole_fairing.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "core/base/errors.h"

namespace hermite {

namespace {

// Mean-value weights tan(θ/2) / |u − v| summed over the triangles on edge v–u (θ their angle at
// v), from the unfaired positions, keyed (v << 32 | u): for graded patches, where they leave a
// flat one-ring where it is while uniform weights pull the small triangles near the boundary
// and the large ones in the middle towards one size, crushing some.
std::unordered_map<std::uint64_t, double> meanValueWeights(const PreparedMesh& prepared, const HolePatch& patch) {
  const TriMesh& mesh = prepared.mesh();
  const auto position = [&](int id) -> Eigen::Vector3d {
    return id >= patch.baseId ? Eigen::Vector3d(patch.vertices.col(id - patch.baseId)) : Eigen::Vector3d(mesh.vertices.col(id));
  };
  std::unordered_map<std::uint64_t, double> meanValue;
  const auto add = [&](int a, int b, int c) {  // the corner at a of triangle (a, b, c)
    const Eigen::Vector3d u = position(b) - position(a), w = position(c) - position(a);
    const double nu = u.norm(), nw = w.norm();
    if (!(nu > 0 && nw > 0)) return;
    const double t = std::tan(0.5 * std::acos(std::clamp(u.dot(w) / (nu * nw), -1.0, 1.0)));
    meanValue[(std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b)] += t / nu;
    meanValue[(std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(c)] += t / nw;
  };
  for (Eigen::Index t = 0; t < patch.triangles.cols(); ++t) {
    const int a = patch.triangles(0, t), b = patch.triangles(1, t), c = patch.triangles(2, t);
    add(a, b, c), add(b, c, a), add(c, a, b);
  }
  for (int v : patch.loop)
    for (const int* t = prepared.trianglesBegin(v); t != prepared.trianglesEnd(v); ++t) {
      int k = 0;
      while (mesh.triangles(k, *t) != v) ++k;
      add(v, mesh.triangles((k + 1) % 3, *t), mesh.triangles((k + 2) % 3, *t));
    }
  return meanValue;
}

using OneRings = std::unordered_map<int, std::vector<int>>;

// One-rings, sorted and without repeats: the patch's edges, plus the original mesh's around the
// boundary vertices.
OneRings patchOneRings(const PreparedMesh& prepared, const HolePatch& patch) {
  OneRings ring;
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
  for (auto& [v, nb] : ring) {
    std::sort(nb.begin(), nb.end());
    nb.erase(std::unique(nb.begin(), nb.end()), nb.end());
  }
  return ring;
}

// Weights of v's one-ring: uniform, or for graded patches the mean-value weights normalised to
// sum 1 (uniform again where none is known).
std::vector<double> ringWeights(int v, const std::vector<int>& nb, bool graded,
                                const std::unordered_map<std::uint64_t, double>& meanValue) {
  std::vector<double> weights(nb.size(), 1.0 / static_cast<double>(nb.size()));
  if (!graded) return weights;
  double sum = 0;
  for (size_t i = 0; i < nb.size(); ++i) {
    const auto it = meanValue.find((std::uint64_t(std::uint32_t(v)) << 32) | std::uint32_t(nb[i]));
    sum += weights[i] = it == meanValue.end() ? 0.0 : it->second;
  }
  if (sum > 0)
    for (double& w : weights) w /= sum;
  else
    std::fill(weights.begin(), weights.end(), 1.0 / static_cast<double>(nb.size()));
  return weights;
}

// min ‖A x − b‖ through the normal equations (sparse LDLᵀ); the rows of the solution.
Eigen::MatrixX3d leastSquares(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixX3d& b) {
  const Eigen::SparseMatrix<double> AtA = A.transpose() * A;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(AtA);
  if (solver.info() != Eigen::Success)
    throw NumericalError("hole fairing: the least-squares normal equations could not be factorised");
  const Eigen::MatrixX3d X = solver.solve(A.transpose() * b);
  if (solver.info() != Eigen::Success || !X.allFinite())
    throw NumericalError("hole fairing: the least-squares solve failed (result not finite)");
  return X;
}

}  // namespace

HolePatch fairPatch(const PreparedMesh& prepared, const HolePatch& patch) {
  HolePatch out = patch;
  const int K = static_cast<int>(patch.vertices.cols());
  if (K == 0) return out;
  const TriMesh& mesh = prepared.mesh();
  auto isNew = [&](int id) { return id >= patch.baseId; };
  auto position = [&](int id) -> Eigen::Vector3d {
    return isNew(id) ? Eigen::Vector3d(patch.vertices.col(id - patch.baseId)) : Eigen::Vector3d(mesh.vertices.col(id));
  };
  const OneRings ring = patchOneRings(prepared, patch);
  // Graded patches: mean-value weights (see meanValueWeights).
  const std::unordered_map<std::uint64_t, double> meanValue =
      patch.graded ? meanValueWeights(prepared, patch) : std::unordered_map<std::uint64_t, double>{};
  // Rows: every vertex of the patch (new and boundary); the unknowns are the new vertices. A thin
  // wedge drops the boundary rows: they would carry the mesh's slope into the patch and bend it
  // through the mesh; without them the patch is a membrane inside the rim's convex hull.
  std::vector<int> rows;
  for (const auto& [v, nb] : ring)
    if (isNew(v) || patch.rimFold == 0) rows.push_back(v);
  std::sort(rows.begin(), rows.end());  // deterministic
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixX3d b = Eigen::MatrixX3d::Zero(static_cast<Eigen::Index>(rows.size()), 3);
  for (size_t r = 0; r < rows.size(); ++r) {
    const int v = rows[r];
    const std::vector<int>& nb = ring.at(v);
    const std::vector<double> weights = ringWeights(v, nb, patch.graded, meanValue);
    // (L x)_v = x_v − weighted mean of the one-ring; known terms go to the right-hand side.
    if (isNew(v)) entries.emplace_back(static_cast<int>(r), v - patch.baseId, 1.0);
    else b.row(static_cast<Eigen::Index>(r)) -= position(v).transpose();
    for (size_t i = 0; i < nb.size(); ++i) {
      const int u = nb[i];
      if (isNew(u)) entries.emplace_back(static_cast<int>(r), u - patch.baseId, -weights[i]);
      else b.row(static_cast<Eigen::Index>(r)) += weights[i] * position(u).transpose();
    }
  }
  Eigen::SparseMatrix<double> A(static_cast<Eigen::Index>(rows.size()), K);
  A.setFromTriplets(entries.begin(), entries.end());
  out.vertices = leastSquares(A, b).transpose();
  return out;
}

}  // namespace hermite
