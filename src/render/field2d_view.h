#pragma once
// The 2D field view: a heat map of f in the diverging colour map
// symmetric about 0, iso-lines at a regular spacing, the zero curve thick and anti-aliased in the
// zero colour (outside the map), samples as dots and normals as arrows on top.
//
// f and ∇f are evaluated on the CPU (the field's threaded batch evaluation) at every pixel centre
// — or on a coarser grid, interpolated bilinearly — uploaded as an RGB32F texture and coloured in
// field2d.frag with the line widths of the CPU reference (core/trace/field2d_reference.h), which this
// view is tested against. The colour legend is drawn with ImGui (render/legend.h).

#include <optional>
#include <string>
#include <vector>

#include "core/base/implicit_field.h"
#include "core/trace/camera.h"
#include "core/trace/field2d_reference.h"
#include "core/trace/image.h"
#include "render/gl/gl_objects.h"

namespace hermite::render {

struct Field2dViewOptions {
  // Colours, line widths, range (0 = max |f| over the evaluated grid inside the bounds) and iso
  // spacing (0 = niceIsoSpacing(range), < 0 = none): the reference's style, so images agree.
  Field2dStyle style;
  // Evaluation grid relative to the pixel grid: 1 = f at every pixel centre (reference quality);
  // 0.5 = a quarter of the evaluations (interactive redraws), bilinear in between.
  double gridScale = 1.0;
  bool showPoints = true;
  bool showNormals = true;
  // Arrow heads on the normals: length of each barb in pixels (0 = plain lines, like the reference).
  double arrowHeadPx = 5.0;
  // view.bounds: outside it iso-lines and the zero curve are not drawn (docs/scene-format.md) and the
  // heat map fades towards `outsideColor` by `outsideMix`. nullopt: the whole view is inside.
  std::optional<Box<2>> bounds;
  std::array<double, 3> outsideColor{1.0, 1.0, 1.0};
  double outsideMix = 0.55;
};

class Field2dView {
 public:
  // Compiles the shaders (EnvironmentError naming file:line on failure). Needs a current GL 4.5
  // context for its whole lifetime.
  Field2dView();

  // Evaluates f and ∇f of `field` over `view` (CPU, all worker threads), uploads them and fixes
  // the colour range and iso spacing. `points` / `normals` (2 × N world coordinates; normals
  // ignored when their count differs) are drawn on top when the options say so.
  void setField(const ImplicitField<2>& field, const View2d& view, const Field2dViewOptions& options,
                const Points<2>& points = Points<2>(2, 0), const Points<2>& normals = Points<2>(2, 0));

  // Draws into the framebuffer bound now, whose viewport must be the view's W × H pixels.
  // Requires setField first (else EnvironmentError). Blend state is restored afterwards.
  void draw();

  double range() const { return range_; }            // the colour map covers [−range, range]
  double isoSpacing() const { return isoSpacing_; }  // ≤ 0: no iso-lines
  const std::optional<View2d>& view() const { return view_; }
  double evaluateMs() const { return evaluateMs_; }  // CPU evaluation of the last setField
  double uploadMs() const { return uploadMs_; }

 private:
  Program heat_;
  Program marks_;
  VertexArray emptyVao_;
  VertexArray marksVao_;
  Buffer marksBuffer_;
  Texture field_;
  std::optional<View2d> view_;
  Field2dViewOptions options_;
  int gridW_ = 0, gridH_ = 0;
  int markCount_ = 0;
  double range_ = 1.0;
  double isoSpacing_ = 0.0;
  double evaluateMs_ = 0;
  double uploadMs_ = 0;
};

// One-shot: draws the view into a new offscreen target of the view's size and reads it back
// (row 0 = top). Needs a current GL context.
ImageRgba8 renderField2d(const ImplicitField<2>& field, const View2d& view, const Field2dViewOptions& options = {},
                         const Points<2>& points = Points<2>(2, 0), const Points<2>& normals = Points<2>(2, 0));

}  // namespace hermite::render
