#pragma once
// The memory of rendering a scene's view at W × H pixels, before the fit and the GL context
// (core/base/memory_check.h): the offscreen framebuffers (OSMesa's colour and depth buffers),
// the tracer's and the field view's per-pixel buffers, the read-back image and the PNG encoder's
// copy, as measured (docs/performance.md, Render memory): a fixed part plus bytes per pixel.

#include <cstdint>

#include "core/base/memory_check.h"

namespace hermite {

// Peak resident memory of `render` per pixel above its fixed part: the 3D view, the larger of the
// 2D and 3D views (measured 182–192 bytes, OSMesa and EGL alike; 2D about 70), rounded up; the
// fixed part measured 139 MB (docs/performance.md, Render memory).
inline constexpr std::uint64_t kRenderBytesPerPixel = 200;
inline constexpr std::uint64_t kRenderFixedBytes = 150'000'000;
inline constexpr const char* kRenderRemedy = "use a smaller --size";

// "rendering 12000 x 12000 pixels (about 200 bytes each)": the fixed part plus the pixels.
PlannedAllocation renderPlan(int width, int height);

}  // namespace hermite
