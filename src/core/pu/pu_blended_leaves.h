#pragma once
// Which leaves of a PU tree the blend fits (docs/maths.md, "No data"): the boxes holding samples,
// their empty neighbours (split where their supports crowd), and the cover boxes of the data
// reach (split until none is many reaches wide). Internal to the PU fit (pu_fit.cpp).

#include <vector>

#include "core/base/cancel_token.h"
#include "core/pu/pu_data_reach.h"
#include "core/pu/pu_leaf_fitter.h"
#include "core/pu/pu_tree.h"

namespace hermite::detail {

// Which leaves the blend uses (docs/maths.md, "No data"). Smooth blend: the boxes holding
// samples, and the empty boxes touching one of them that are at most twice its longest edge and
// whose support at `overlap` holds a sample (a support that must grow to reach any sample would
// fit distant ones, e.g. across the thin boxes of a flat cloud) —
// a margin of about one box beyond the data, so the cells of a coarser mesh across the surface
// still have data at every corner, without the far extrapolations of big empty boxes. Each is
// fitted on its own support (borrowing a neighbour's fit instead extrapolates that fit a whole box
// and grows sheets). Hard blend: every leaf. Per leaf of `tree`: 1 when the blend fits it, else 0.
template <int Dim>
std::vector<char> blendedLeaves(const PuTree<Dim>& tree, PuBlend blend, double overlap);

// Splits the blended empty leaves whose supports would hold more than limits.max samples;
// `blended` follows the tree's new leaves. Smooth blend only.
template <int Dim>
void splitCrowdedBlended(PuTree<Dim>& tree, std::vector<char>& blended, const PuOptions& options,
                         const LeafFitter<Dim>& fitter, const SupportLimits& limits);

// Splits the empty leaves within reach of the data that are many reaches wide; `blended` follows.
template <int Dim>
void refineCover(PuTree<Dim>& tree, const PuDataReach<Dim>& reach, std::vector<char>& blended,
                 const CancelToken* cancel);

// Marks kCover the leaves not yet blended that some sample reaches.
template <int Dim>
void blendReachCover(const PuTree<Dim>& tree, const PuDataReach<Dim>& reach, std::vector<char>& blended);

}  // namespace hermite::detail
