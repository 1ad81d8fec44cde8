#pragma once
// Contouring a partition-of-unity fit without its stray pockets (docs/maths.md, "Stray pockets").
//
// Far from its samples a local fit extrapolates, and where a support had to grow (a sparse
// region, or a crack or fin thinner than the sample spacing) it can put f's zero set where no
// surface is: a small void inside the solid or a blob outside, sometimes joined to the true
// surface. The samples' winding number (cloud_winding.h) knows the side there: about 1 inside,
// 0 outside, ½ only near the sampled surface. So each contour marching cubes makes is reviewed
// before the anchors count its pieces:
//  1. pieces other than the largest, of at most 5 % of the triangles, whose vertices' mean
//     winding number is above kPieceInside (a void in the solid) or below kPieceOutside (a
//     blob outside) are left out. A true piece of the surface has about ½ on it; the tip of a
//     part thinner than a few spacings that the grid cut off has less (0.27–0.41 on the dino's
//     claws), so the bound on that side stays well under the guard's kGuardOutside;
//  2. vertices of the largest piece with no sample in the 3 × 3 × 3 cells around their own
//     (occupied_cells.h; cells half the contour grid's, but never wider than 1.3 sample
//     spacings √(A / N)), or with none within 1.0 spacing and half a spacing or more off the
//     tangent planes of the samples within 2.5 on average (or, on average outside them, half a
//     spacing outside one), or with none within 1.5 spacings, whose winding number is decided
//     (above kGuardInside or below kGuardOutside) are strays: a pocket joined to the surface.
//     Up to 1 024 such far vertices are first filtered by a winding number summed directly
//     with every sample standing for A / N: only where that decides is the samples' one built.
//     Only those outside the guard region so far count, with f on the other side of a decided
//     winding number along their own grid edge or at a corner of the cell-sized cube about them
//     (else a guard would change nothing).
//  3. after the rounds below, pieces that could be tips a grid cut off a part thinner than a
//     cell (cut_tips.h: small, within a cell diagonal of the largest) whose mean winding number
//     is below kTipWinding (and not below kPieceOutside) are left out: a true surface has
//     about ½, the tip of a thin part less (the dino's claws 0.27–0.41, the Stanford dragon's
//     fin tips 0.34–0.35). They count in MarchingReport::droppedTips.
// Then, if the contour kept has strays, f's sign is overruled by the winding number within
// kGuardCells cell diagonals of each stray (winding_guard_field.h) and the cells about them are
// contoured again (contour_patch.h; the whole grid when they are many or a seam stays open),
// and again while new strays appear, at most kGuardRounds times — unless the first contour's
// strays are more than kMaxStrayShare of its vertices: then the samples do not describe a closed
// surface densely enough for their winding number to be trusted (parts thinner than the
// sampling: CGAL's boeing has 7–9 %; the Stanford dragon 0–0.04 %; the self-intersecting cow
// and man at 20 000 samples just over 1 %, which their guard closes), and it stays as it is.
// Only for fields with no-data regions (the smooth blend) and at least kGuardMinSamples samples:
// the winding number needs a densely sampled surface.

#include <memory>
#include <vector>

#include "core/base/implicit_field.h"
#include "core/mesh/marching_cubes.h"
#include "core/mesh/occupied_cells.h"
#include "core/points/cloud_winding.h"
#include "core/points/hermite_samples.h"

namespace hermite {

inline constexpr int kGuardMinSamples = 1000;
inline constexpr double kGuardCells = 3.0;
inline constexpr int kGuardRounds = 2;
inline constexpr double kMaxStrayShare = 0.02;
inline constexpr double kPieceInside = 0.6;
inline constexpr double kPieceOutside = 0.15;
inline constexpr double kTipWinding = 0.45;

// Step 2's plane test for points put on the zero set after the review (chord refinement's new
// vertices, between the grid's): x is a stray when no sample lies within 1.0 spacing √(A / N) of
// it (A the contour's area), the samples within 2.5 put it half a spacing or more off their
// tangent planes on average (or, on average outside them, half a spacing outside one) or none
// lies within 1.5, and the samples' winding number at x is decided (up to 1 024 such points are
// first filtered by a sum over the samples, each standing for A / N, as step 2's far vertices
// are). Only for a field and samples contourWithoutStrays reviews (appliesTo).
class StrayTest {
 public:
  // `samples` must outlive the test; `box` is the contour's; `cancel` is polled while the winding
  // number is built.
  StrayTest(const HermiteSamples<3>& samples, const Box<3>& box, double area, const CancelToken* cancel = nullptr);
  static bool appliesTo(const ImplicitField<3>& field, const HermiteSamples<3>& samples);
  // Per column of X, whether it is a stray.
  std::vector<char> operator()(const Points<3>& X) const;
  double spacing() const { return spacing_; }
  const OccupiedCells& cells() const { return bySpacing_; }  // the samples in cells of one spacing
  // The samples' winding number, built on first use and kept (the review's and this test's; one
  // caller at a time).
  const std::shared_ptr<const CloudWinding<3>>& winding() const;

 private:
  const HermiteSamples<3>& samples_;
  double spacing_;
  OccupiedCells bySpacing_;  // the samples in cells of one spacing
  const CancelToken* cancel_;
  mutable std::shared_ptr<const CloudWinding<3>> winding_;
};

struct StrayReport {
  int strayVertices = 0;  // strays of the first contour
  int rounds = 0;         // contours again with the guard
  bool tooMany = false;   // more strays than kMaxStrayShare of the vertices: no guard
  int droppedPieces = 0;  // pieces left out for their winding number
  // The review's plane test, for points put on the zero set after it (chord refinement); null
  // when no review ran or its strays were too many to trust the winding number. It reads the
  // samples given to contourWithoutStrays: use it while they live.
  std::shared_ptr<const StrayTest> planes;
};

// marchingCubes(field, box, options, report), then the steps above with the fit's samples.
// `guarded` receives the guard field when step 2 ran (null otherwise): the field later passes
// over the mesh (chord refinement) should read.
TriMesh contourWithoutStrays(const ImplicitField<3>& field, const Box<3>& box, const MarchingOptions& options,
                             const HermiteSamples<3>& samples, MarchingReport* report, StrayReport* stray,
                             std::unique_ptr<ImplicitField<3>>* guarded);

}  // namespace hermite
