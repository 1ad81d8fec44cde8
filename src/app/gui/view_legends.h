#pragma once
// The legends of the view: every colour with a meaning gets one, in the primary view's
// lower-right corner.
//  - 2D: the heat map's colour bar with values (inside f < 0, outside f > 0).
//  - 3D implicit: the surface colours (seen from outside / from inside, i.e. inside-out) and,
//    with the slice plane on, its heat map's colour bar above them.
//  - patch editor with the torus error shown: the error ramp from 0 to the largest error.
//  - hole filling: the input mesh, the added triangles, the hole rims and the ring samples.

#include "app/gui/scene_view.h"

namespace hermite::app {

struct GuiContext;

void drawViewLegends(const GuiContext& ctx, const SceneViewResult& view);

}  // namespace hermite::app
