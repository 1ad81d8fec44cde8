#pragma once
// What the patch editor shows for a PatchSpec: the grid, its tessellation, and for the torus
// preset the error of every tessellation vertex against the exact torus (|X_patch − X_torus| at
// the same (u, v)) and the error table of the torus study (`patch-table`) for the current splits
// and domain. Built on the fit worker like an implicit fit.

#include <vector>

#include "core/patch/torus_patch_study.h"
#include "scene/patch_document.h"

namespace hermite {

struct PatchDisplay {
  PatchGrid grid;
  PatchGrid::Tessellation mesh;
  std::vector<double> vertexError;   // per tessellation vertex; empty unless the torus is the reference
  double maxError = 0;
  std::vector<PatchStudyRow> table;  // torus preset: the study row of the current splits (and 1×1)
  double tessellateMs = 0;
};

// The torus is the reference for the "torus" and "zero-twist" presets (their knots sample it).
bool patchHasTorusReference(const PatchSpec& spec);

PatchDisplay buildPatchDisplay(const PatchSpec& spec);

}  // namespace hermite
