#include "core/mesh/contour_patch.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>

#include "core/mesh/marching_cubes.h"
#include "core/mesh/open_slivers.h"

namespace hermite {

namespace {

constexpr int kIndexBits = 20;  // per axis: grids of up to 2²⁰ lines

// A grid edge as a hash key: its axis and the indices of its lower end.
std::uint64_t edgeKey(const GridEdge& e) {
  std::uint64_t k = static_cast<std::uint64_t>(e.axis);
  for (int a = 0; a < 3; ++a) k = k << kIndexBits | static_cast<std::uint64_t>(e.at[a]);
  return k;
}

// Whether the edge lies on a face of the block (within its closed extent, on one of its planes).
bool onBlockFace(const GridEdge& e, const CellBlock& b) {
  bool face = false;
  for (int a = 0; a < 3; ++a) {
    if (a == e.axis) {
      if (e.at[a] < b.lo[a] || e.at[a] >= b.hi[a]) return false;
      continue;
    }
    if (e.at[a] < b.lo[a] || e.at[a] > b.hi[a]) return false;
    face = face || e.at[a] == b.lo[a] || e.at[a] == b.hi[a];
  }
  return face;
}

bool insideBlock(const std::array<int, 3>& cell, const CellBlock& b) {
  for (int a = 0; a < 3; ++a)
    if (cell[a] < b.lo[a] || cell[a] >= b.hi[a]) return false;
  return true;
}

bool touching(const CellBlock& x, const CellBlock& y) {
  for (int a = 0; a < 3; ++a)
    if (x.lo[a] > y.hi[a] || y.lo[a] > x.hi[a]) return false;
  return true;
}

CellBlock hull(const CellBlock& x, const CellBlock& y) {
  CellBlock h;
  for (int a = 0; a < 3; ++a) h.lo[a] = std::min(x.lo[a], y.lo[a]), h.hi[a] = std::max(x.hi[a], y.hi[a]);
  return h;
}

// Which of the mesh's triangles lie in a cell of the blocks: a triangle lies inside its cube (no
// fan puts three vertices on one cube face), so its centroid's cell is its cube.
std::vector<char> trianglesInBlocks(const TriMesh& mesh, const GridLines<3>& lines, const std::vector<CellBlock>& blocks) {
  std::vector<char> in(static_cast<std::size_t>(mesh.triangleCount()), 0);
#pragma omp parallel for schedule(static)
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    Vec<3> c = Vec<3>::Zero();
    for (int k = 0; k < 3; ++k) c += mesh.vertices.col(mesh.triangles(k, t));
    c /= 3.0;
    std::array<int, 3> cell{};
    for (int a = 0; a < 3; ++a) cell[a] = gridCellOf(lines[a], c[a]);
    for (const CellBlock& b : blocks)
      if (insideBlock(cell, b)) in[static_cast<std::size_t>(t)] = 1;
  }
  return in;
}

// The block's own lines (copies of the grid's, so its vertices' coordinates are the grid's exactly).
GridLines<3> blockLines(const GridLines<3>& lines, const CellBlock& b) {
  GridLines<3> sub;
  for (int a = 0; a < 3; ++a) sub[a].assign(lines[a].begin() + b.lo[a], lines[a].begin() + b.hi[a] + 1);
  return sub;
}

// Whether a vertex of the mesh sits where an orphan does.
bool orphanLeft(const TriMesh& mesh, const std::vector<Vec<3>>& orphanPositions) {
  std::vector<std::array<double, 3>> orphans;
  for (const Vec<3>& p : orphanPositions) orphans.push_back({p[0], p[1], p[2]});
  std::sort(orphans.begin(), orphans.end());
  for (Eigen::Index v = 0; v < mesh.vertices.cols(); ++v)
    if (std::binary_search(orphans.begin(), orphans.end(),
                           std::array<double, 3>{mesh.vertices(0, v), mesh.vertices(1, v), mesh.vertices(2, v)}))
      return true;
  return false;
}

// The mesh being patched: the old vertices, the kept triangles, then each block's pass.
class Patch {
 public:
  Patch(const TriMesh& mesh, const GridLines<3>& lines, const std::vector<CellBlock>& blocks)
      : mesh_(mesh), lines_(lines), gone_(trianglesInBlocks(mesh, lines, blocks)) {
    out_.vertices = mesh.vertices;
    out_.normals = mesh.normals;
    const std::size_t V = static_cast<std::size_t>(mesh.vertexCount());
    onKept_.assign(V, 0);
    matched_.assign(V, 0);
    std::vector<char> onGone(V, 0);
    for (int t = 0; t < mesh.triangleCount(); ++t) {
      std::vector<char>& on = gone_[static_cast<std::size_t>(t)] ? onGone : onKept_;
      for (int k = 0; k < 3; ++k) on[static_cast<std::size_t>(mesh.triangles(k, t))] = 1;
      if (!gone_[static_cast<std::size_t>(t)]) triangles_.push_back(mesh.triangles.col(t));
    }
    for (std::size_t v = 0; v < V; ++v)
      if (onGone[v]) {
        const GridEdge e = gridEdgeOf(lines, mesh.vertices.col(static_cast<Eigen::Index>(v)));
        if (e.axis >= 0) faceVertex_.emplace(edgeKey(e), static_cast<int>(v));
      }
  }

  // Adds the block's pass. A vertex on the block's faces is its old twin; one without (the
  // old contour's review left out a piece there) is an orphan, kept as a new vertex.
  void add(const TriMesh& pass, const CellBlock& b) {
    std::vector<int> id(static_cast<std::size_t>(pass.vertexCount()));
    for (int v = 0; v < pass.vertexCount(); ++v) {
      const GridEdge e = gridEdgeOf(lines_, pass.vertices.col(v));
      const bool onFace = e.axis >= 0 && onBlockFace(e, b);
      const auto it = onFace ? faceVertex_.find(edgeKey(e)) : faceVertex_.end();
      if (it != faceVertex_.end()) {
        id[static_cast<std::size_t>(v)] = it->second;
        matched_[static_cast<std::size_t>(it->second)] = 1;
      } else {
        if (onFace) orphans_.push_back(pass.vertices.col(v));
        id[static_cast<std::size_t>(v)] = static_cast<int>(added_.size()) + mesh_.vertexCount();
        added_.push_back(v);
      }
    }
    appendVertices(pass);
    for (int t = 0; t < pass.triangleCount(); ++t)
      triangles_.emplace_back(id[static_cast<std::size_t>(pass.triangles(0, t))],
                              id[static_cast<std::size_t>(pass.triangles(1, t))],
                              id[static_cast<std::size_t>(pass.triangles(2, t))]);
  }

  // The patched mesh; null when an old vertex joining kept triangles to replaced ones has no twin
  // in the passes (the seam would open).
  std::optional<TriMesh> finish() {
    for (int t = 0; t < mesh_.triangleCount(); ++t) {
      if (!gone_[static_cast<std::size_t>(t)]) continue;
      for (int k = 0; k < 3; ++k) {
        const std::size_t v = static_cast<std::size_t>(mesh_.triangles(k, t));
        if (onKept_[v] && !matched_[v]) return std::nullopt;
      }
    }
    out_.triangles.resize(3, static_cast<Eigen::Index>(triangles_.size()));
    for (std::size_t t = 0; t < triangles_.size(); ++t) out_.triangles.col(static_cast<Eigen::Index>(t)) = triangles_[t];
    dropUnusedVertices(out_);
    return std::move(out_);
  }
  const std::vector<Vec<3>>& orphans() const { return orphans_; }

 private:
  void appendVertices(const TriMesh& pass) {
    const Eigen::Index first = out_.vertices.cols(), n = static_cast<Eigen::Index>(added_.size()) + mesh_.vertexCount() - first;
    out_.vertices.conservativeResize(3, first + n);
    out_.normals.conservativeResize(3, first + n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const int v = added_[static_cast<std::size_t>(first - mesh_.vertexCount() + i)];
      out_.vertices.col(first + i) = pass.vertices.col(v);
      out_.normals.col(first + i) = pass.normals.col(v);
    }
  }

  const TriMesh& mesh_;
  const GridLines<3>& lines_;
  std::vector<char> gone_;      // per old triangle: in a block
  std::vector<char> onKept_;    // per old vertex: used by a kept triangle
  std::vector<char> matched_;   // per old vertex: a pass's face vertex is it
  std::unordered_map<std::uint64_t, int> faceVertex_;  // grid edge → old vertex on it (of replaced triangles)
  std::vector<Eigen::Vector3i> triangles_;
  std::vector<int> added_;      // per new vertex: its index in its pass
  std::vector<Vec<3>> orphans_; // new vertices on a block's faces
  TriMesh out_;
};

}  // namespace

std::vector<CellBlock> cellBlocksAround(const GridLines<3>& lines, const std::vector<Vec<3>>& centres, double reach) {
  std::vector<CellBlock> blocks;
  for (const Vec<3>& c : centres) {
    CellBlock b;
    for (int a = 0; a < 3; ++a) {
      const std::vector<double>& l = lines[a];
      const int n = static_cast<int>(l.size()) - 1;
      b.lo[a] = std::max(gridCellOf(l, std::clamp(c[a] - reach, l.front(), l.back())) - 1, 0);
      b.hi[a] = std::min(gridCellOf(l, std::clamp(c[a] + reach, l.front(), l.back())) + 2, n);
    }
    const auto near = std::find_if(blocks.begin(), blocks.end(), [&](const CellBlock& x) { return touching(x, b); });
    if (near != blocks.end()) *near = hull(*near, b);
    else blocks.push_back(b);
  }
  for (bool merged = true; merged;) {
    merged = false;
    for (std::size_t i = 0; i < blocks.size() && !merged; ++i)
      for (std::size_t j = i + 1; j < blocks.size() && !merged; ++j)
        if (touching(blocks[i], blocks[j])) {
          blocks[i] = hull(blocks[i], blocks[j]);
          blocks.erase(blocks.begin() + static_cast<std::ptrdiff_t>(j));
          merged = true;
        }
  }
  return blocks;
}

std::optional<TriMesh> patchContour(const TriMesh& mesh, const ImplicitField<3>& field, const GridLines<3>& lines,
                                    const Vec<3>& h, const std::vector<CellBlock>& blocks,
                                    const MarchingOptions& options) {
  MarchingOptions pass = options;
  pass.progress = {};  // a pass per block: progress from 0 to 1 for each would mislead
  Patch patch(mesh, lines, blocks);
  for (const CellBlock& b : blocks) patch.add(marchingCubesPass(field, blockLines(lines, b), h, pass), b);
  std::optional<TriMesh> out = patch.finish();
  if (!out) return out;
  if (options.review) options.review(*out, lines);
  // An orphan still there is a seam that opened: the review did not leave its piece out again.
  if (orphanLeft(*out, patch.orphans())) return std::nullopt;
  dropGridSlivers(*out, field, h);
  return out;
}

}  // namespace hermite
