#pragma once
// Framing what a view shows: the box of the samples (implicit modes), of the patch grid (patch)
// or of the mesh to fill (holefill), and the camera that sees it whole. F uses it; so do `render`
// and opening a scene in the patch and hole-filling modes when the scene names no camera of its
// own (their content is not placed about the origin, where the default camera looks).

#include <optional>

#include "app/gui/fit_worker.h"

namespace hermite::app {

// The samples' own box; their view bounds (padded) when the samples span nothing (one point).
template <int Dim>
Box<Dim> samplesBox(const ViewSpec& view, const Points<Dim>& points);

// The box a 3D view of `fit` shows and the room to leave around it (a factor ≥ 1); none for a 2D
// fit or an empty mesh.
struct ShownBox {
  Box<3> box;
  double margin = 1.05;
};
std::optional<ShownBox> shownBox3d(const FitOutcome& fit);

// `camera` moved along its view direction (eye − target) and re-aimed so that `shown` fills a
// view of the given aspect (width / height); orthographic views take the returned half height.
struct FramedCamera {
  CameraSpec camera;
  double halfHeight = 1.5;  // view2d.half_height for orthographic 3D views
};
FramedCamera framedCamera(const CameraSpec& camera, const ShownBox& shown, double aspect);

// A patch or hole-filling scene without a camera of its own (view.camera is the default): the
// scene with its camera framing what the mode shows at view.size; any other scene unchanged.
Scene framedOnLoad(Scene scene);

}  // namespace hermite::app
