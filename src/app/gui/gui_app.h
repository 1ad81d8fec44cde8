#pragma once
// The interactive application: a frame loop over panel and tool objects that each own their
// state and draw their own UI, on whatever GL context is current — the GLFW window
// (gui_window.cpp) or an offscreen one (UI tests, `render --ui`, the latency bench). Input
// arrives as a FrameInput (the window fills it from GLFW callbacks, tests script it), so the same
// code is driven by a user and by a test.
//
// Per frame: feed ImGui → adopt finished fits → dropped files, shortcuts and the view's mouse
// gestures (camera, samples, gizmo, slice plane, patch handles) unless ImGui wants the input →
// panels (which edit the Document) → submit a refit when what a fit reads changed (not the view) → redraw
// the view image when the fit, the view or the size changed → overlays → ImGui draw. What the
// parts share lives in a GuiContext (gui_context.h); fits run on a FitWorker thread and the last
// good result stays on screen until a newer one arrives.

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "app/gui/frame_phases.h"
#include "app/gui/gui_context.h"
#include "app/gui/gui_input.h"
#include "app/panels/compare_panel.h"
#include "app/panels/data_panel.h"
#include "app/panels/diagnostics_panel.h"
#include "app/panels/explore_panel.h"
#include "app/panels/fit_panel.h"
#include "app/panels/hole_fill_panel.h"
#include "app/panels/patch_editor.h"
#include "app/panels/transform_panel.h"
#include "app/panels/view_panel.h"
#include "app/tools/camera_tool.h"
#include "app/tools/sample_tool.h"
#include "app/tools/slice_plane_tool.h"
#include "app/tools/transform_gizmo.h"
#include "render/imgui_renderer.h"
#include "render/ui_font.h"

struct ImGuiContext;

namespace hermite::app {

class GuiApp {
 public:
  // Needs a current GL 4.5 context; creates its own ImGui context.
  GuiApp(Document document, GuiOptions options = {});
  ~GuiApp();
  // Not copyable: its parts hold references to its context (and FitWorker owns a thread).

  // Runs one frame and draws it into the framebuffer bound now (width × height of the input).
  void frame(const FrameInput& input);

  Document& document() { return ctx_.document; }
  FitWorker& worker() { return ctx_.fits.worker(); }
  // The fit on screen (the last good one), or null.
  const FitOutcome* shownFit() const { return ctx_.fits.shown().get(); }
  // The fit on screen when it is of the document's mode, else null (fit_presenter.h).
  const FitOutcome* currentFit() const { return ctx_.currentFit(); }
  std::uint64_t shownVersion() const { return ctx_.fits.shownVersion(); }
  // Fits submitted to the worker so far (view, camera and overlay changes submit none).
  int fitSubmissions() const { return ctx_.fits.submissions(); }
  const GuiStatus& status() const { return ctx_.status; }
  // Screen position (view pixels) of a patch handle of the current document; nullopt if behind.
  std::optional<Vec<2>> patchHandleScreenPosition(const PatchHandle& h) const { return patch_.handlePosition(h); }
  // Work for the view (bakes, refinement) runs in the background: the window keeps drawing frames.
  bool viewPending() const { return ctx_.image.pending(); }
  // A frame drawn now would show something new without input: a document changed since the last
  // frame (by a caller between frames), a finished fit to adopt, the view settling after a
  // gesture, background view work for the GL thread (frame_pacing.h), or a finished mesh export.
  bool wantsFrame() const {
    return ctx_.document.version() != framedVersion_ || ctx_.fits.worker().hasResult() || ctx_.image.wantsFrame() ||
           data_.exportFinished();
  }
  // A fit, a view job or a radius sweep runs: the window draws a few frames a second for progress.
  bool busy();
  // The view on screen shows the fit of the document's current version, at its final quality.
  bool viewIsCurrent() const {
    return shownFit() && shownVersion() == ctx_.document.version() && ctx_.image.shows(shownFit());
  }
  // The view on screen shows the fit of the document's current version at some quality (a
  // drag's coarse bake counts; its finer bake may still be on its way).
  bool viewShowsCurrentFit() const {
    return shownFit() && shownVersion() == ctx_.document.version() && viewResult().drawnFrom == shownFit();
  }
  int selectedSample() const { return ctx_.selected; }
  bool quitRequested() const { return quit_; }
  // The view image last drawn (without panels) and how long it took.
  const SceneViewResult& viewResult() const { return ctx_.image.result(); }
  RadiusExplorer& explorer() { return explore_.explorer(); }

  // Panels' visibility (`render --ui` shows them all; tests toggle them) and the compare view.
  PanelVisibility& panels = ctx_.panels;
  CompareSettings& compare = ctx_.compare;

  // Position of sample i and of its normal's tip in view pixels (add viewOrigin() for the
  // window); nullopt when not visible.
  std::optional<Vec<2>> sampleScreenPosition(int i) const { return samples_.samplePosition(i); }
  std::optional<Vec<2>> normalTipScreenPosition(int i) const { return samples_.normalTipPosition(i); }
  // Screen rectangles (min x, min y, max x, max y) of the named widgets drawn last frame
  // ("fit.radius", "fit.kernel", "diagnostics.cancel", ...): how scripted UI tests find them.
  std::optional<std::array<float, 4>> widgetRect(const std::string& name) const;
  const std::map<std::string, std::array<float, 4>>& widgetRects() const { return ctx_.widgets; }
  Vec<2> viewOrigin() const { return ctx_.view.origin(); }
  Vec<2> viewSize() const { return Vec<2>(ctx_.view.w, ctx_.view.h); }  // the whole view, both halves when comparing
  // The transform gizmo (tests switch it on and find its handles).
  void setGizmoVisible(bool on) { ctx_.showGizmo = on; }
  // Saves a screenshot of the next frame to `path` (with or without the panels).
  void requestScreenshot(const std::string& path, bool withUi);
  // The UI scale now (Ctrl + / Ctrl − / Ctrl 0 change it; the fonts follow at the next frame).
  float uiScale() const { return ctx_.uiScale; }
  // The pixel height of the UI type the last frame was drawn with.
  float fontPixels() const { return fonts_.regular ? fonts_.regular->FontSize : 0.0f; }
  // Glyphs drawn with the fallback glyph (a code point the font lacks) over all frames so far
  // (render/glyph_misses.h): zero when every message shows in full.
  int glyphMisses() const { return glyphMisses_; }
  // The presenter mode's caption for what is on screen now (presenter_caption.h).
  std::string presenterCaption() const;
  // Where the last frame's time went (frame_phases.h); the present / buffer swap is not in it.
  const FramePhases& lastPhases() const { return phases_; }
  // The last frame's ImGui draw data: vertices and draw commands (the rasteriser's share of a
  // frame grows with them; HERMITE_GUI_LOG writes them).
  int lastDrawVertices() const { return drawVertices_; }
  int lastDrawCommands() const { return drawCommands_; }

 private:
  void handleShortcuts(const FrameInput& in);
  void handleViewInput(const FrameInput& in);
  void pressInView(const FrameInput& in, const Vec<2>& mouse);  // a button went down over the view
  void drawPanels();
  void drawOverlays();
  void recordSampleMarks();
  void renderFrame();
  void takeScreenshot(const FrameInput& in);
  void handleScaleKeys(const FrameInput& in);
  // Re-rasterises the fonts and rescales the style when ctx_.uiScale changed (before NewFrame).
  void applyUiScale();

  GuiContext ctx_;
  ImGuiContext* imgui_ = nullptr;
  std::unique_ptr<render::ImGuiRenderer> imguiRenderer_;
  render::UiFonts fonts_;
  int glyphMisses_ = 0;
  FramePhases phases_;
  int drawVertices_ = 0, drawCommands_ = 0;
  // Tools in the view.
  CameraTool camera_{ctx_};
  SampleTool samples_{ctx_};
  SlicePlaneTool slicePlane_{ctx_};
  TransformGizmo gizmo_{ctx_};
  // Panels.
  DataPanel data_{ctx_};
  ViewPanel view_{ctx_, camera_};
  ExplorePanel explore_{ctx_};
  PatchEditor patch_{ctx_};
  HoleFillPanel holeFill_{ctx_};

  Vec<2> lastMouse_ = Vec<2>::Zero();
  // A left press that orbits or pans once the mouse moves, and selects `sample` (−1: clears the
  // selection) when it is released in place.
  struct Click {
    Vec<2> at;
    int sample = -1;
  };
  std::optional<Click> click_;
  std::array<bool, 3> prevMouseDown_{};
  std::array<bool, 512> prevKeys_{};
  std::uint64_t framedVersion_ = 0;  // the document version at the end of the last frame
  bool quit_ = false;
};

}  // namespace hermite::app
