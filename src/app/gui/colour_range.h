#pragma once
// The 2D heat-map range shared by every image of an r sweep (`sweep`, the r explorer's
// thumbnails), so that the images compare.

#include "scene/scene_file.h"

namespace hermite::app {

// ± this many field units: half of view2d.half_height (f is close to the signed distance near
// the data, since ∇f = n at the samples, so one range in world units colours every r alike).
// 0 (each image its own range) in 3D, which has no heat map.
inline double sharedColourRange(const Scene& scene) {
  return scene.dimension() == 2 ? 0.5 * scene.view.halfHeight2d : 0.0;
}

}  // namespace hermite::app
