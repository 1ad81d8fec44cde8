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
//
// A gap thinner than a cell (a crack between two parts of the solid, or between a limb and the
// body) comes out the other way round: the grid fills most of it and keeps, at most, a small
// pocket of the outside enclosed by the solid — a closed piece of negative signed volume, on the
// crack's walls but away from the surface around the crack's mouth (the Stanford dragon sampled
// with 1 000 000 points, at 256³: 10 triangles, three cells from the body). Such a pocket is
// left out when it is not the largest piece, at most kTipShare of the triangles, closed, of
// negative signed volume, and a sample within kGapReach cell diagonals of its box lies more than
// kGapOff cell diagonals from every vertex of the mesh (the filled gap's walls) — however far it
// lies from the largest piece — or, like a tip, a missed sample lies within a cell diagonal. The
// crack's samples need not count as missed: the fit itself barely opens a gap that narrow, so
// the probes along ∇f find none. A true cavity is meshed with its samples on it (and a scan
// sees no cavity at all).

#include <vector>

#include "core/base/geometry.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

inline constexpr double kTipShare = 0.01;
inline constexpr double kGapReach = 2.0;
inline constexpr double kGapOff = 1.5;

// The pieces of a mesh that could be such tips or pockets: not the largest, at most kTipShare of
// the triangles, and with a vertex within `cellDiagonal` of one of the largest piece (a tip) or
// closed with negative signed volume (a pocket, whether or not that near; `gap` says so).
struct TipCandidates {
  std::vector<int> piece;      // per triangle: its piece (vertexConnectedComponents)
  int count = 0;               // pieces
  std::vector<int> pieces;     // the candidates
  std::vector<Box<3>> reach;   // per candidate: its bounding box grown by `cellDiagonal`
  std::vector<char> gap;       // per candidate: a pocket of the outside
};
TipCandidates tipCandidates(const TriMesh& mesh, double cellDiagonal);

// Per piece of `c` (tipCandidates(mesh, cellDiagonal)): whether dropCutTips leaves it out, with
// the same `missed` and `samples`; `gaps` (optional) counts the pockets among them.
std::vector<char> cutTipsToDrop(const TriMesh& mesh, const TipCandidates& c, const Points<3>& missed,
                                double cellDiagonal, const Points<3>* samples, int* gaps = nullptr);

// The samples (their columns) within half a cell diagonal of the pockets among the pieces `drop`
// leaves out (cutTipsToDrop): the walls of a gap the grid closed at its mouth, which leave the
// mesh with their pocket. The refined pass (marching_cubes.cpp) counts them as missed. A true
// cavity, with its samples on it and none off the mesh beside it, has none.
std::vector<int> samplesOnPockets(const TriMesh& mesh, const TipCandidates& c, const std::vector<char>& drop,
                                  double cellDiagonal, const Points<3>& samples);

// Removes the cut-off tips and pockets (as above) and the vertices no triangle uses; `missed`
// are the positions of the missed samples, `cellDiagonal` the uniform grid cell's, `samples`
// all of them (none: only a missed sample is a pocket's evidence). Returns how many pieces were
// removed; `gaps` (optional) receives how many of them were pockets.
int dropCutTips(TriMesh& mesh, const Points<3>& missed, double cellDiagonal, int* gaps = nullptr,
                const Points<3>* samples = nullptr);

}  // namespace hermite
