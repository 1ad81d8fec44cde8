#pragma once
// Tips of thin parts that a contour grid cut off (docs/maths.md, Contouring).
//
// Where a part is thinner than a cell (a fin, a claw), the grid can step over its neck and the
// tip comes out as a small closed piece of its own, about a sample spacing from the rest — a
// finer grid moves the cut but need not remove it (the Stanford dragon's fins at 256³ and 512³).
// Such a piece is not a separate part of the object: the samples between it and the body
// (anchors the grid missed, marching_anchors.h) say the surface goes on there. It is left out
// when it is
//   - not the largest piece, and at most kTipShare of the triangles;
//   - within one cell diagonal of the largest piece (a vertex of each that close);
//   - within one cell diagonal of a sample a grid misses (the uniform one or, when the mesh is
//     the refined grid's, that one).
// A small piece that is really separate has no missed sample at its side, or lies farther off.
// The first two make the candidates that the stray-pocket review also tests by their winding
// number (stray_pockets.h), where the neck's samples sit in cells with a sign change.

#include <vector>

#include "core/base/geometry.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

inline constexpr double kTipShare = 0.01;

// The pieces of a mesh that could be such tips: not the largest, at most kTipShare of the
// triangles, with a vertex within `cellDiagonal` of one of the largest piece.
struct TipCandidates {
  std::vector<int> piece;      // per triangle: its piece (vertexConnectedComponents)
  int count = 0;               // pieces
  std::vector<int> pieces;     // the candidates
  std::vector<Box<3>> reach;   // per candidate: its bounding box grown by `cellDiagonal`
};
TipCandidates tipCandidates(const TriMesh& mesh, double cellDiagonal);

// Removes the cut-off tips (as above) and the vertices no triangle uses; `missed` are the
// positions of the missed samples, `cellDiagonal` the uniform grid cell's.
// Returns how many pieces were removed.
int dropCutTips(TriMesh& mesh, const Points<3>& missed, double cellDiagonal);

}  // namespace hermite
