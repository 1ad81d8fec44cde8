#pragma once
// The torus error study of `hermite-lab patch-table`: the domain [U0,U1] × [V0,V1] of the torus
// (patch_grid.h) split into n × m equal Hermite patches built from exact knot data. In each
// patch, N × N local parameters uniform in [0, 1] (ends included); per coordinate the patch's
// error is the spectral norm (largest singular value) of the N × N matrix of |X_patch − X_torus|
// element by element; a row reports the mean of that error over the patches, per coordinate,
// and the largest |Hermite − Bézier (de Casteljau)| difference over all samples.

#include <array>
#include <vector>

#include "core/base/memory_check.h"

namespace hermite {

struct PatchStudyOptions {
  int samples = 15;                          // N ≥ 2
  std::array<double, 4> domain{0, 1, 0, 1};  // U0, U1, V0, V1 (U0 < U1, V0 < V1)
  std::vector<std::array<int, 2>> splits{{1, 1}, {2, 1}, {2, 2}, {3, 3}};  // n along u, m along v
};

struct PatchStudyRow {
  std::array<int, 2> splits;
  std::array<double, 3> error;    // mean spectral-norm error per coordinate
  double hermiteBezierMaxDiff;    // max |Hermite − de Casteljau| over every sample and coordinate
};

// Peak memory of the study with N samples: the three N × N error matrices and the SVD's
// working copy of one of them, 4 N² doubles (core/base/memory_check.h).
PlannedAllocation patchStudyPlan(int samples);

// Throws InputError for N < 2, an empty domain or a split < 1; MemoryLimitError when
// patchStudyPlan does not fit in the available memory.
std::vector<PatchStudyRow> torusPatchStudy(const PatchStudyOptions& options);

}  // namespace hermite
