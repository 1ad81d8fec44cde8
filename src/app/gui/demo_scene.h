#pragma once
// The scene the program opens without an argument. Built in, so the binary runs anywhere.

namespace hermite::app {

// The Stanford bunny, 600 samples, Wendland HRBF with a linear term at r = 0.6 (about 8 mean
// spacings): a kernel with a radius, so the r slider is the first thing that does something — a
// clean surface here, a spurious plane (the linear term alone, where no support reaches) below
// r ≈ 0.35.
inline constexpr const char* kDemoSceneJson = R"({
  "version": 1,
  "mode": "implicit3d",
  "data": { "preset": "bunny", "count": 600 },
  "fit": { "method": "hrbf", "kernel": "wendland", "radius": 0.6, "polynomial": "linear" }
})";

}  // namespace hermite::app
