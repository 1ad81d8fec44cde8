#pragma once
// Shading directions for the baked trace: one RGBA8 texture fetch per hit instead of the six
// fetches of a central difference of the interpolant.
//
// At every sample, the central difference of the samples one cell apart (neighbours clamped to
// the grid, as the shader's CLAMP_TO_EDGE clamps). Trilinear interpolation of these vertex
// differences is the central difference of the trilinear interpolant with step one cell — the
// interpolant is linear in the samples, and a shift by one cell moves every weight onto the
// neighbouring sample — so the filtered texture gives the direction the six fetches gave, up to
// normalising before interpolating and the 8-bit storage (≈ 0.3° per component).

#include <cstdint>
#include <vector>

#include "core/trace/volume_bake.h"

namespace hermite::render {

// R³ RGBA8 texels, x fastest: (n + 1) / 2 · 255 rounded, n the unit central-difference
// direction; (128, 128, 128) — n ≈ 0, shaded as facing the viewer — where the difference
// vanishes or is not finite. Alpha 255, or 0 where a zero at the sample would be no surface
// (VolumeBake::noData): filtered, the baked march's test of a zero. Threaded (OpenMP).
std::vector<std::uint8_t> bakedNormalTexels(const VolumeBake& bake);

// The unit direction a texel holds (for tests): 2 · byte / 255 − 1 per component.
Vec<3> decodeBakedNormal(const std::uint8_t* texel);

}  // namespace hermite::render
