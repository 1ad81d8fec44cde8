// Cut-off tips of thin parts (cut_tips.h).

#include "core/mesh/cut_tips.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/mesh/near_mesh_distance.h"

namespace hermite {

namespace {

// The triangles of each piece `wanted` says yes to (`of`: a piece per triangle), in one pass.
std::vector<std::vector<int>> trianglesOf(const TriMesh& mesh, const std::vector<int>& of,
                                          const std::vector<char>& wanted) {
  std::vector<std::vector<int>> out(wanted.size());
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const size_t i = static_cast<size_t>(of[static_cast<size_t>(t)]);
    if (wanted[i]) out[i].push_back(t);
  }
  return out;
}

// The vertices of the triangles, each once.
std::vector<int> verticesOf(const TriMesh& mesh, const std::vector<int>& triangles) {
  std::vector<int> v;
  for (int t : triangles)
    for (int k = 0; k < 3; ++k) v.push_back(mesh.triangles(k, t));
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

// Whether the triangles close up: every undirected edge is used by exactly two of them.
bool closedUp(const TriMesh& mesh, const std::vector<int>& triangles) {
  std::vector<std::uint64_t> edges;
  for (int t : triangles)
    for (int k = 0; k < 3; ++k) edges.push_back(edgeKey(mesh.triangles(k, t), mesh.triangles((k + 1) % 3, t)));
  std::sort(edges.begin(), edges.end());
  for (size_t i = 0; i < edges.size(); i += 2)
    if (i + 1 >= edges.size() || edges[i] != edges[i + 1] || (i + 2 < edges.size() && edges[i + 2] == edges[i]))
      return false;
  return true;
}

// Whether the piece (its `triangles`) is closed with negative signed volume: a pocket of the
// outside enclosed by the solid.
bool enclosesOutside(const TriMesh& mesh, const std::vector<int>& triangles) {
  return !triangles.empty() && closedUp(mesh, triangles) && signedVolume(mesh, triangles) < 0;
}

Box<3> grownBy(Box<3> box, double d) {
  box.lo.array() -= d;
  box.hi.array() += d;
  return box;
}

// Whether a sample within kGapReach cell diagonals d of `reach` (a pocket's box grown by d) lies
// more than kGapOff d from every vertex of the mesh: on a gap's wall that the grid filled. Every
// point of a marching-cubes surface is within d of a vertex (its cell's), so a sample on the
// surface is within d of one.
bool samplesOffMesh(const TriMesh& mesh, const Points<3>& samples, const Box<3>& reach, double d) {
  const Box<3> around = grownBy(reach, (kGapReach - 1) * d), vertexBox = grownBy(around, kGapOff * d);
  std::vector<Vec<3>> near;
  for (int v = 0; v < mesh.vertexCount(); ++v)
    if (vertexBox.contains(mesh.vertices.col(v))) near.push_back(mesh.vertices.col(v));
  for (Eigen::Index i = 0; i < samples.cols(); ++i) {
    if (!around.contains(samples.col(i))) continue;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Vec<3>& x : near) nearest = std::min(nearest, (x - samples.col(i)).squaredNorm());
    if (nearest > kGapOff * kGapOff * d * d) return true;
  }
  return false;
}

// Whether a vertex of `near` lies within d of a vertex of `piece`.
bool within(const TriMesh& mesh, const std::vector<int>& piece, const std::vector<int>& near, double d) {
  for (int a : piece)
    for (int b : near)
      if ((mesh.vertices.col(a) - mesh.vertices.col(b)).squaredNorm() <= d * d) return true;
  return false;
}

}  // namespace

TipCandidates tipCandidates(const TriMesh& mesh, double cellDiagonal) {
  TipCandidates c;
  if (mesh.triangleCount() == 0) return c;
  const MeshPieces p(mesh);
  c.piece = p.of;
  c.count = p.count();
  if (c.count <= 1) return c;
  std::vector<char> small(static_cast<size_t>(c.count), 0);
  for (int i = 0; i < c.count; ++i)
    small[static_cast<size_t>(i)] = i != p.largest && p.size[static_cast<size_t>(i)] <= kTipShare * mesh.triangleCount();
  if (std::find(small.begin(), small.end(), 1) == small.end()) return c;
  std::vector<char> wanted = small;
  wanted[static_cast<size_t>(p.largest)] = 1;
  const std::vector<std::vector<int>> triangles = trianglesOf(mesh, p.of, wanted);
  const std::vector<int> body = verticesOf(mesh, triangles[static_cast<size_t>(p.largest)]);
  const std::vector<Box<3>> boxes = componentBoxes(mesh, p.of, c.count);
  for (int i = 0; i < c.count; ++i) {
    if (!small[static_cast<size_t>(i)]) continue;
    const Box<3> reach = grownBy(boxes[static_cast<size_t>(i)], cellDiagonal);
    std::vector<int> near;  // the largest piece's vertices in reach
    for (int v : body)
      if (reach.contains(mesh.vertices.col(v))) near.push_back(v);
    const bool tip = within(mesh, verticesOf(mesh, triangles[static_cast<size_t>(i)]), near, cellDiagonal);
    const bool pocket = enclosesOutside(mesh, triangles[static_cast<size_t>(i)]);
    if (!tip && !pocket) continue;
    c.pieces.push_back(i);
    c.reach.push_back(reach);
    c.gap.push_back(pocket);
  }
  return c;
}

std::vector<char> cutTipsToDrop(const TriMesh& mesh, const TipCandidates& c, const Points<3>& missed,
                                double cellDiagonal, const Points<3>* samples, int* gaps) {
  const bool pockets = samples && samples->cols() > 0;
  std::vector<char> drop(static_cast<size_t>(c.count), 0);
  for (size_t k = 0; k < c.pieces.size(); ++k) {
    char& go = drop[static_cast<size_t>(c.pieces[k])];
    for (Eigen::Index m = 0; m < missed.cols() && !go; ++m) go = c.reach[k].contains(missed.col(m));
    if (c.gap[k]) {
      go = go || (pockets && samplesOffMesh(mesh, *samples, c.reach[k], cellDiagonal));
      if (go && gaps) ++*gaps;
    }
  }
  return drop;
}

std::vector<int> samplesOnPockets(const TriMesh& mesh, const TipCandidates& c, const std::vector<char>& drop,
                                  double cellDiagonal, const Points<3>& samples) {
  std::vector<char> notPocket(static_cast<size_t>(c.count), 1);  // the pieces to leave out of `walls`
  for (size_t k = 0; k < c.pieces.size(); ++k)
    if (c.gap[k] && drop[static_cast<size_t>(c.pieces[k])]) notPocket[static_cast<size_t>(c.pieces[k])] = 0;
  if (std::find(notPocket.begin(), notPocket.end(), 0) == notPocket.end()) return {};
  TriMesh walls = mesh;
  dropComponents(walls, c.piece, notPocket);
  const double reach = 0.5 * cellDiagonal;
  const std::vector<double> d = distancesToMeshWithin(walls, samples, reach);
  std::vector<int> on;
  for (size_t i = 0; i < d.size(); ++i)
    if (d[i] < reach) on.push_back(static_cast<int>(i));
  return on;
}

int dropCutTips(TriMesh& mesh, const Points<3>& missed, double cellDiagonal, int* gaps, const Points<3>* samples) {
  if (gaps) *gaps = 0;
  if (missed.cols() == 0 && !(samples && samples->cols() > 0)) return 0;
  const TipCandidates c = tipCandidates(mesh, cellDiagonal);
  return dropComponents(mesh, c.piece, cutTipsToDrop(mesh, c, missed, cellDiagonal, samples, gaps));
}

}  // namespace hermite
