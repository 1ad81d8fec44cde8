// Cut-off tips of thin parts (cut_tips.h).

#include "core/mesh/cut_tips.h"

#include <algorithm>
#include <vector>

namespace hermite {

namespace {

struct Pieces {
  std::vector<int> of;      // per triangle
  std::vector<int> size;    // triangles per piece
  std::vector<Box<3>> box;  // per piece, when there are several
  int largest = 0;
};

// Marching cubes' pieces meet at no vertex, so the vertex union-find (no edge sort) finds them;
// the sizes and boxes only when there is more than one.
Pieces piecesOf(const TriMesh& mesh) {
  Pieces p;
  int count = 0;
  p.of = vertexConnectedComponents(mesh, &count);
  p.size.assign(static_cast<size_t>(count), 0);
  for (int c : p.of) ++p.size[static_cast<size_t>(c)];
  p.largest = static_cast<int>(std::max_element(p.size.begin(), p.size.end()) - p.size.begin());
  if (count > 1) p.box = componentBoxes(mesh, p.of, count);
  return p;
}

// The vertices of each piece `wanted` says yes to (each once), in one pass over the triangles.
std::vector<std::vector<int>> verticesOf(const TriMesh& mesh, const Pieces& p, const std::vector<char>& wanted) {
  std::vector<std::vector<int>> out(wanted.size());
  for (int t = 0; t < mesh.triangleCount(); ++t) {
    const size_t i = static_cast<size_t>(p.of[static_cast<size_t>(t)]);
    if (wanted[i])
      for (int k = 0; k < 3; ++k) out[i].push_back(mesh.triangles(k, t));
  }
  for (std::vector<int>& v : out) {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }
  return out;
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
  const Pieces p = piecesOf(mesh);
  c.piece = p.of;
  c.count = static_cast<int>(p.size.size());
  if (c.count <= 1) return c;
  std::vector<char> small(static_cast<size_t>(c.count), 0);
  for (int i = 0; i < c.count; ++i)
    small[static_cast<size_t>(i)] = i != p.largest && p.size[static_cast<size_t>(i)] <= kTipShare * mesh.triangleCount();
  if (std::find(small.begin(), small.end(), 1) == small.end()) return c;
  std::vector<char> wanted = small;
  wanted[static_cast<size_t>(p.largest)] = 1;
  const std::vector<std::vector<int>> vertices = verticesOf(mesh, p, wanted);
  for (int i = 0; i < c.count; ++i) {
    if (!small[static_cast<size_t>(i)]) continue;
    Box<3> grown = p.box[static_cast<size_t>(i)];
    grown.lo.array() -= cellDiagonal;
    grown.hi.array() += cellDiagonal;
    std::vector<int> near;  // the largest piece's vertices in reach
    for (int v : vertices[static_cast<size_t>(p.largest)])
      if (grown.contains(mesh.vertices.col(v))) near.push_back(v);
    if (!within(mesh, vertices[static_cast<size_t>(i)], near, cellDiagonal)) continue;
    c.pieces.push_back(i);
    c.reach.push_back(grown);
  }
  return c;
}

int dropCutTips(TriMesh& mesh, const Points<3>& missed, double cellDiagonal) {
  if (missed.cols() == 0) return 0;
  const TipCandidates c = tipCandidates(mesh, cellDiagonal);
  std::vector<char> drop(static_cast<size_t>(c.count), 0);
  for (size_t k = 0; k < c.pieces.size(); ++k)
    for (Eigen::Index m = 0; m < missed.cols() && !drop[static_cast<size_t>(c.pieces[k])]; ++m)
      drop[static_cast<size_t>(c.pieces[k])] = c.reach[k].contains(missed.col(m));
  return dropComponents(mesh, c.piece, drop);
}

}  // namespace hermite
