#pragma once
// The scene the program opens without an argument. Built in, so the binary runs anywhere.

namespace hermite::app {

// The Stanford bunny, 600 samples, cubic HRBF with a linear term: the classic first fit.
inline constexpr const char* kDemoSceneJson = R"({
  "version": 1,
  "mode": "implicit3d",
  "data": { "preset": "bunny", "count": 600 },
  "fit": { "method": "hrbf", "kernel": "cubic", "polynomial": "linear" }
})";

}  // namespace hermite::app
