#pragma once
// Contouring an implicit field's zero set over a box (docs/maths.md, Contouring):
// marching squares (2D → polylines) and marching cubes (3D → a triangle mesh).
//
// Both sample f on a regular grid (evaluateBatch, threaded), place one vertex on every grid edge
// whose end values differ in sign (f < 0 inside, f ≥ 0 outside), and resolve the ambiguous faces
// (cells) by a sign at the saddle point of the bilinear interpolant of their corner values: the
// interpolant's own there in 2D (the asymptotic decider), f's in 3D (face_decider.h). Every
// decision about a face depends on that face's four values and grid lines only, so the two cubes sharing
// a face build the same segments there: the output is watertight where the zero set is closed
// inside the box, and manifold (every edge of the mesh is used by exactly two triangles, each
// vertex's triangles form one fan). Each cube's face segments are chained into closed polygons and
// triangulated by a fan that never puts a diagonal on a cube face (so no edge can repeat in the
// neighbouring cube), or around a centre vertex where no such fan exists.
//
// Orientation (docs/maths.md, Conventions): triangles are counter-clockwise seen from outside (face normals
// along +∇f); 2D polylines run counter-clockwise around the inside (outside on the right).
// Vertices are refined by Newton's iteration restricted to their grid edge,
// t ← t − f / (∇f · (b − a)), safeguarded by the sign bracket (Illinois false position when a
// step leaves it) and kept within [τ, 1 − τ] of the edge (τ = 1e-3), so the mesh's combinatorics
// stay those of the grid and no triangle degenerates; normals are ∇f / ‖∇f‖ at the final positions.
//
// No data (ImplicitField::validNear with the cell diagonal as margin, validOnZeroSet at the
// vertices): a cube (square) with a corner where the field has no data makes no geometry, a grid
// edge with such an end gets no vertex, and a polygon (segment) none of whose vertices the field
// accepts on its zero set is left out; the contour is open there.

#include <array>
#include <functional>

#include "core/base/cancel_token.h"
#include "core/base/geometry.h"
#include "core/mesh/grid_lines.h"
#include "core/mesh/tri_mesh.h"

namespace hermite {

struct MarchingOptions {
  int resolution = 64;  // cells along the box's longest side (≥ 1); the others in proportion
  int newtonSteps = 4;  // Newton iterations along each vertex's grid edge (0: linear interpolation)
  // Skip f at grid points far from the zero set (an octree, marching_cull.h): blocks of 64³, 32³,
  // …, 4³ cells are tested coarse to fine; a block with |f(c)| > L·r at its centre c (L =
  // lipschitzBound over the block, or over its 16³ ancestor for smaller blocks where that is
  // finite; r its half-diagonal; L is not computed where |f(c)| ≤ ‖∇f(c)‖·r, since L ≥ ‖∇f(c)‖)
  // cannot change sign, so its points only need that sign, and only the 4³ blocks
  // left need f at every point. Exact: the mesh is identical to the dense one (every value the mesh
  // uses — on sign-changing edges and ambiguous faces — lies in a block that is not skipped).
  bool cull = true;
  // Cooperative cancellation (null: none): polled between batches of at most 2¹⁴ evaluations of
  // f, so a cancel is seen within ~100 ms; throws Cancelled.
  const CancelToken* cancel = nullptr;
  // Receives the fraction (0 … 1) of the grid evaluations done, on the calling thread, after each
  // batch (empty: none). The culling octree and the vertex refinement are not counted.
  std::function<void(double)> progress = {};
  // Points on the zero set, world coordinates (the fit's samples; null: none; 3D only). An anchor
  // is missed when its own cell has no sign change, the field passes through it and the zero set
  // there is thinner than a cell diagonal along ∇f (marching_anchors.h): a part of the surface the
  // grid steps over. When that splits the mesh into pieces, the grid is refined and contoured
  // again: the cells of the missed anchors are cut into kAnchorSplit along every axis, each cut a
  // whole grid plane, so the grid stays rectilinear and the mesh watertight; the finer mesh is
  // kept when it has fewer pieces. The samples on a pocket of a thin gap the grid closed at its
  // mouth (cut_tips.h) count as missed when they are at least kRefineOffShare of all. Not refined
  // (and reported) when the mesh is one piece anyway, or when the cuts would more than double an
  // axis's cells or need more than half the available memory.
  const Points<3>* anchors = nullptr;
  // Reviews each contour marching cubes makes — the uniform one, and the refined one the anchors
  // ask for — with the grid lines it was made on, before its pieces are counted (empty: none; 3D
  // only): it may leave out pieces that are not surface (stray_pockets.h).
  std::function<void(TriMesh&, const GridLines<3>&)> review = {};
};

inline constexpr int kAnchorReach = 0;  // cells around a missed anchor's own that are cut too, per side
inline constexpr int kAnchorSplit = 4;  // parts each of them is cut into
// Missed anchors more than half a cell diagonal off the uniform mesh, as a share of all anchors,
// from which the refined pass runs for a mesh in one piece: deciding faces by f keeps a thin part
// the grid steps over joined by a ribbon a cell wide that lies off its samples (CGAL's man at
// 200 000 samples, 256³: 188 such of 340 missed; 99th percentile of the distances 0.23 % of the
// diagonal in one piece, 0.08 % refined), where a truncated rim (femur: 73 of 275, spool: 0 of
// 73) leaves them within a cell. The same share of samples on the pockets of thin gaps runs it
// too (CGAL's femur, a crack near one end: docs/performance.md, "Pockets with samples on their
// walls run the refined pass").
inline constexpr double kRefineOffShare = 5e-4;

// What the contouring measured.
struct MarchingReport {
  std::array<int, 3> cells{0, 0, 0};  // cells per axis (the third is 1 in 2D)
  double evaluateMs = 0;              // grid values (the bulk of the time for RBF fields)
  long long gridPoints = 0;           // points of the grid
  long long evaluatedPoints = 0;      // of which f was evaluated (the rest culled, plus block centres)
  double totalMs = 0;
  double maxAbsF = 0;                 // max |f| over the edge and centre vertices after refinement
  int centreVertices = 0;             // polygons fanned around a centre vertex (centre_vertices.h)
  int centresOffZeroSet = 0;          // of those, centres with no root of f on their segment (not in maxAbsF)
  int missedAnchors = 0;              // anchors the uniform grid missed (MarchingOptions::anchors)
  // What was done about them: Refined, or why not.
  enum class Refinement { None, Refined, OnePiece, TooLarge, NoGain, NotNearer } refinement = Refinement::None;
  std::array<int, 3> refinedCells{0, 0, 0};  // cells per axis of the refined grid; 0 when not refined
  int stillMissed = 0;                // anchors the refined grid missed too (missedAnchors when not refined)
  // The smallest grid step (world units). A vertex lies at least 10⁻³ of its edge from a grid
  // point, so the mesh's smallest triangles scale with its square.
  double minStep = 0;
  // Open pieces (cut where the field has no data) with less area than the smallest face of a
  // uniform grid cell, left out of the mesh (open_slivers.h).
  int droppedSlivers = 0;
  // Small pieces beside samples the grid misses: tips of parts thinner than a cell that it cut
  // off, left out of the mesh (cut_tips.h). contourWithoutStrays adds those its winding number
  // shows (stray_pockets.h).
  int droppedTips = 0;
  // Small closed pockets of the outside enclosed by the solid beside samples the grid misses:
  // what the grid kept of a gap thinner than a cell, left out of the mesh (cut_tips.h).
  int droppedGaps = 0;
};

}  // namespace hermite
