#pragma once
// Normals for raw clouds (docs/maths.md, Normal estimation): a normal line per point from its k
// nearest neighbours, then one orientation for all (after Hoppe et al. 1992).
//
// Thin parts: two sheets closer than the neighbourhood share neighbours. The line: PCA when its
// plane through pᵢ holds all k within half the sheet band (sheetBand × the neighbourhood
// radius); else the best of the hyperplanes through Dim of the k, scored (MSAC) as one sheet
// through pᵢ or two parallel sheets, refitted over the inliers of each sheet about its mean.
// The orientation: every k-nearest-neighbour edge is classified by its direction d = pⱼ − pᵢ
// and by whether each end sees the other on its own sheet (within the band, nearer its own
// sheet than its second):
//   along a sheet  one sheet, d leaves neither tangent plane by more than asin(gapSine), the
//                  normals agree (|nᵢ·nⱼ| ≥ agreeCosine): the orientation is copied;
//   across a gap   off one another's sheets (or d along both normals), normals parallel
//                  (|nᵢ·nⱼ| ≥ acrossCosine): two sheets of a closed surface face each other, so
//                  the orientation is reversed;
//   otherwise      (creases, folds, noise) the crease rule — d·nᵢ and d·nⱼ have opposite signs
//                  across a convex or concave crease — where d leaves both tangent planes more
//                  steeply than the normals agree, else copied.
// Patches of up to 16 points grow along the first kind; every edge between two patches votes on
// their relative orientation, and a maximum spanning tree of the patches by the summed votes
// orients them, so that no single wrong edge turns a sheet over. Estimated lines of samples
// between two sheets (a rim's) are not trusted, so no patch joins the sheets through them.
//
// Folds: after the orientation, the normals around the rim that joins two close sheets are
// re-estimated from the two oriented sheets (fold_normals.h): between them the rim's direction,
// away from the sheets at a convex rim, towards them at a concave one.
//
// Seeds: each part of the graph that no fixed normal reaches starts at its extreme point along
// a coordinate axis (the largest coordinate among the points not yet oriented, over the axes,
// the one whose normal is most aligned with its axis) with its normal pointing along +axis:
// the outward side of a closed shape there.

#include "core/base/geometry.h"

namespace hermite {

struct NormalEstimationOptions {
  int neighbours = 10;       // k ≥ Dim (PCA needs a spread); 10 fits typical scanned clouds
  double gapSine = 0.5;      // an edge leaving a tangent plane by more than 30° crosses a gap
  double agreeCosine = 0.5;  // normals more than 60° apart are not along one sheet
  double acrossCosine = 0.85;  // across a gap: normals within 32° of parallel, d within 32° of them
  double sheetBand = 0.3;  // × the neighbourhood radius: farther off a tangent plane is another sheet
};

// Unit normals (Dim × N) for the columns of `points` (Dim × N, N ≥ 2). InputError when N < 2.
template <int Dim>
Points<Dim> estimateNormals(const Points<Dim>& points, const NormalEstimationOptions& options = {});

// Fills the columns of `normals` (Dim × N, beside `points`) that are exactly zero with estimated
// unit normals oriented consistently with the non-zero ones (which are kept, unnormalised, and
// seed the orientation); all zero is estimateNormals. Returns how many were filled.
// InputError when a normal is missing and N < 2.
template <int Dim>
int completeNormals(const Points<Dim>& points, Points<Dim>& normals, const NormalEstimationOptions& options = {});

// Orientation check of given normals: the fraction of the k-nearest-neighbour edges (each point
// to its k nearest) that run along a sheet (the edge lies within 30° of both tangent planes and
// the normals are within 60° of parallel) whose normals point opposite ways (nᵢ·nⱼ < 0). Zero
// normals and their edges are skipped; 0 when no edge runs along a sheet. Above 50 000 points
// an even stride of 50 000 of them query their neighbours. Measured on CGAL's
// data: oni.pwn 0.11 %, a noisy sphere with 0.75 % of its normals inward 0.39 %, cube.pwn
// (unoriented lines, half inward) 1.4 %, random signs ≈ 50 %.
template <int Dim>
double orientationDisagreement(const Points<Dim>& points, const Points<Dim>& normals,
                               const NormalEstimationOptions& options = {});

// Re-orients given normal lines (Dim × N, none zero; the lengths and lines are kept, only signs
// change) by the propagation estimateNormals uses, seeded at each part's extreme point. Then,
// per part, the given signs decide when they mostly agree: a part where at most a third of them
// agree with the propagation is turned over (consistently given inward normals stay inward).
// Returns how many normals changed sign. InputError when a normal is zero.
template <int Dim>
int orientNormalLines(const Points<Dim>& points, Points<Dim>& normals, const NormalEstimationOptions& options = {});

// Flips every normal (the GUI's "flip" button): n ↦ −n.
template <int Dim>
void flipNormals(Points<Dim>& normals) {
  normals = -normals;
}

}  // namespace hermite
