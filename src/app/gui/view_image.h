#pragma once
// The view's image: the shown fit drawn by a SceneViewRenderer (and the compare fit in the right
// half), redrawn only when the fit, the view, the size or the quality changed — interactive
// (half-resolution 3D, coarse 2D grid) during a gesture, settled a few frames after — or when
// background work for it arrived, and put on screen as ImGui background images with the compare
// labels and the legends (view_legends.h). Unless fits are synchronous (tests, `render --ui`), the
// 3D view's bakes and exact refinement run on the renderer's worker and arrive over later frames.

#include <optional>

#include "app/gui/scene_view.h"
#include "render/gl/gl_objects.h"

namespace hermite::app {

struct GuiContext;

class ViewImage {
 public:
  // Redraws when something it shows changed; failures go to the status line.
  void redrawIfStale(GuiContext& ctx);
  // Adds the images (and labels, legend) to ImGui's background draw list.
  void draw(const GuiContext& ctx) const;
  // The primary image last drawn (without panels) and how long it took.
  const SceneViewResult& result() const { return view_; }
  // Its pixels (row 0 = top), read back when it stayed on the GPU.
  ImageRgba8 pixels() const;
  // The image on screen was drawn from `fit`, at its final quality (no background work left).
  bool shows(const FitOutcome* fit) const { return drawn_ && drawn_->fit == fit && !pending(); }
  // Bakes or refinement for the view run on the renderer's worker (scene_view.h).
  bool pending() const { return renderer_.pending(); }
  // The next frame would draw something new: the view has not settled since the last gesture
  // (the settled quality starts a few frames after it), or background work waits for the GL
  // thread (frame_pacing.h).
  bool wantsFrame() const;

 private:
  // What the images on screen were drawn from.
  struct Drawn {
    const FitOutcome* fit = nullptr;
    const FitOutcome* compare = nullptr;
    ViewSpec view;
    int width = 0, height = 0;
    double colourRange = 0;
    ViewQuality quality = ViewQuality::Settled;
    bool compareOn = false;
    bool operator==(const Drawn&) const = default;
  };
  void drawCompareLabels(const GuiContext& ctx, float x0, float w) const;

  SceneViewRenderer renderer_, compareRenderer_;  // left / whole, right half
  SceneViewResult view_, compareView_;
  render::Texture viewTexture_, compareTexture_;
  std::optional<Drawn> drawn_;
  int interactFrames_ = 1 << 20;  // frames since the last camera / drag gesture (settled after a few)
};

}  // namespace hermite::app
