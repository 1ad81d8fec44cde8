#pragma once
// The interactive application: one object that runs a frame at a time on whatever GL
// context is current — the GLFW window (gui_window.cpp) or an offscreen one (UI tests,
// `render --ui`, the latency bench). Input arrives as a FrameInput (the window fills it from GLFW
// callbacks, tests script it), so the same code is driven by a user and by a test.
//
// Per frame: feed ImGui → adopt finished fits → shortcuts and view tools (camera, sample
// select / drag / normal rotate / add / delete) unless ImGui wants the input → panels (which
// edit the Document) → submit a refit when the document's version moved → redraw the view image
// when the fit, the view or the size changed → ImGui draw. The fit runs on a FitWorker thread;
// the last good result stays on screen until a newer one arrives.

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/gui/document.h"
#include "app/gui/explorer.h"
#include "app/gui/fit_worker.h"
#include "app/gui/scene_view.h"
#include "render/gl/gl_objects.h"
#include "render/imgui_renderer.h"
#include "scene/radius_sweep.h"

struct ImGuiContext;

namespace hermite::app {

// One frame of input, in framebuffer pixels (row 0 = top). Key codes are GLFW's.
struct FrameInput {
  int width = 800, height = 600;
  double mouseX = -1, mouseY = -1;        // < 0: no mouse over the window
  std::array<bool, 3> mouseDown{};        // left, right, middle
  float wheel = 0;                        // notches this frame, + = away from the user
  std::array<bool, 512> keysDown{};       // GLFW key codes
  bool ctrl = false, shift = false, alt = false;
  std::vector<unsigned> characters;       // text input this frame
  std::vector<std::string> droppedFiles;  // paths dropped onto the window this frame
  double deltaSeconds = 1.0 / 60.0;
};

struct GuiOptions {
  bool iniFile = false;             // ImGui's layout file (off in tests)
  bool synchronousFits = false;     // wait for each fit inside the frame (render --ui, tests)
  std::string screenshotDirectory = ".";
  // Wall-clock figures differ run to run: `render --ui` hides them (same input → same bytes).
  bool showTimings = true;
};

// What the program did last, for the status bar and tests.
struct GuiStatus {
  std::string message;
  bool error = false;
};

class GuiApp {
 public:
  // Needs a current GL 4.5 context; creates its own ImGui context.
  GuiApp(Document document, GuiOptions options = {});
  ~GuiApp();
  GuiApp(const GuiApp&) = delete;
  GuiApp& operator=(const GuiApp&) = delete;

  // Runs one frame and draws it into the framebuffer bound now (width × height of the input).
  void frame(const FrameInput& input);

  Document& document() { return document_; }
  const Document& document() const { return document_; }
  FitWorker& worker() { return worker_; }
  // The fit on screen (the last good one), or null.
  const FitOutcome* shownFit() const { return shown_.get(); }
  // The fit on screen when it is of the document's mode, else null: right after a mode switch
  // (2D ⇄ 3D, patch, hole filling) the previous mode's result stays on screen until the new fit
  // arrives, and tools that read samples must not take it for the current one.
  const FitOutcome* currentFit() const {
    return shown_ && shown_->scene.mode == document_.scene().mode ? shown_.get() : nullptr;
  }
  std::uint64_t shownVersion() const { return shownVersion_; }
  const GuiStatus& status() const { return status_; }
  // Screen position (view pixels) of a patch handle of the current document; nullopt if behind.
  std::optional<Vec<2>> patchHandleScreenPosition(const PatchHandle& h) const;
  // The view on screen shows the fit of the document's current version.
  bool viewIsCurrent() const {
    return shown_ && shownVersion_ == document_.version() && drawn_ && drawn_->fit == shown_.get();
  }
  int selectedSample() const { return selected_; }
  bool quitRequested() const { return quit_; }
  // The view image last drawn (without panels) and how long it took.
  const SceneViewResult& viewResult() const { return view_; }
  RadiusExplorer& explorer() { return explorer_; }

  // Panels' visibility (`render --ui` shows them all; tests toggle them).
  struct Panels {
    bool data = true, fit = true, compare = false, transform = false, diagnostics = true, view = true, explore = false, help = false;
    bool hideUi = false;  // Tab: only the view
  } panels;

  // Compare: the right half of a split view shows the same data fitted another way.
  enum class CompareWith { RbfOffset, Hrbf, OtherKernel, OtherRadius };
  struct CompareSettings {
    bool enabled = false;
    CompareWith with = CompareWith::RbfOffset;
    KernelType kernel = KernelType::Gaussian;
    double radius = 0.5;
  } compare;

  // Position of sample i and of its normal's tip in view pixels (add viewOrigin() for the
  // window); nullopt when not visible.
  std::optional<Vec<2>> sampleScreenPosition(int i) const;
  std::optional<Vec<2>> normalTipScreenPosition(int i) const;
  // Screen rectangles (min x, min y, max x, max y) of the named widgets drawn last frame
  // ("fit.radius", "fit.kernel", "diagnostics.cancel", ...): how scripted UI tests find them.
  std::optional<std::array<float, 4>> widgetRect(const std::string& name) const;
  Vec<2> viewOrigin() const { return Vec<2>(viewX_, viewY_); }
  Vec<2> viewSize() const { return Vec<2>(viewW_, viewH_); }  // view pixels (the whole view, both halves when comparing)
  // The transform gizmo (tests switch it on and find its handles).
  void setGizmoVisible(bool on) { showGizmo_ = on; }
  // Saves a screenshot of the next frame to `path` (with or without the panels).
  void requestScreenshot(const std::string& path, bool withUi);

 private:
  // gui_app.cpp
  void feedImGui(const FrameInput& in);
  void adoptFinishedFits();
  void submitIfStale();
  void redrawViewIfStale();
  void drawViewImage();
  void takePendingScreenshot(const FrameInput& in);
  void renderFrame();
  void setStatus(std::string message, bool error = false);
  std::optional<Scene> compareScene(const Scene& scene) const;
  // tools/view_tools.cpp: camera and sample manipulation
  void handleShortcuts(const FrameInput& in);
  void handleViewInput(const FrameInput& in);
  void handleDroppedFiles(const FrameInput& in);
  int pickSample(const Vec<2>& mouse, bool* onTip) const;
  void moveSelected(const Vec<2>& mouse, bool tip);
  void addSampleAt(const Vec<2>& mouse);
  void deleteSelected();
  void flipSelected();
  void orbit(double dx, double dy);
  void pan(double dx, double dy);
  void zoom(double notches, const Vec<2>& mouse);
  void fitToView();
  void resetView();
  // panels/panels.cpp
  void recordWidget(const std::string& name);  // the last item's rectangle
  void drawPanels();
  void drawDataPanel();
  void drawFitPanel();
  void drawComparePanel();
  void drawDiagnosticsPanel();
  void drawViewPanel();
  void drawExplorePanel();
  void drawHelpOverlay();
  void drawStatusBar();
  void drawSelectionOverlay();
  // panels/transform_panel.cpp: the Transform panel and gizmo
  struct GizmoHandle {
    enum Kind { Translate, Rotate, Scale } kind = Translate;
    int axis = 0;
  };
  void drawTransformPanel();
  void drawGizmo();
  bool pressGizmo(const Vec<2>& mouse);
  void dragGizmo(const Vec<2>& mouse);
  std::optional<GizmoHandle> pickGizmo(const Vec<2>& mouse) const;
  std::vector<GizmoHandle> gizmoHandles() const;
  std::vector<Vec<2>> gizmoShape(const GizmoHandle& h) const;
  bool gizmoFrame(Vec<3>& pivot, double& size) const;
  std::optional<Vec<2>> worldToView(const Vec<3>& x) const;
  bool showGizmo_ = false;
  GizmoHandle gizmo_;
  Vec<2> lastGizmoMouse_ = Vec<2>::Zero();
  // panels/hole_fill_panel.cpp: hole filling (mode "holefill")
  void drawHoleFillPanel();
  // panels/patch_panel.cpp: the patch editor (mode "patch")
  void drawPatchPanel();
  void drawPatchHandles();
  void drawHoleLabels();  // each hole's index at its boundary's centre
  void openHoleFillMesh(const std::string& path);  // hole-fill mode: the mesh to fill
  bool pressPatchHandle(const Vec<2>& mouse);  // true when a handle was grabbed
  void dragPatchHandle(const Vec<2>& mouse, const FrameInput& in);
  // tools/view_tools.cpp: the slice plane, dragged along its normal in the 3D view
  bool pressSlicePlane(const Vec<2>& mouse);
  void dragSlicePlane(const Vec<2>& mouse);
  std::optional<double> sliceLineParameter(const Vec<2>& mouse) const;
  double sliceOffsetExtent() const;  // offsets in [−extent, extent] cut the view bounds
  // Helpers
  void openScene(const std::string& path);
  void loadPreset(const std::string& name, SceneMode mode);
  void saveScene(const std::string& path);
  void editFit(const FitSpec& fit, const std::string& label);
  void screenshotNow(const std::string& path, bool withUi, const FrameInput& in);
  int dimension() const { return document_.scene().dimension(); }
  // Width in pixels of the view that the camera and the 2D view map mouse positions to: the left
  // half while the compare view is split, else the whole view.
  int primaryViewWidth() const { return drawn_ && drawn_->compareOn ? viewW_ / 2 : viewW_; }
  const Scene& scene() const { return document_.scene(); }

  Document document_;
  GuiOptions options_;
  ImGuiContext* imgui_ = nullptr;
  std::unique_ptr<render::ImGuiRenderer> imguiRenderer_;
  FitWorker worker_;
  std::uint64_t submittedVersion_ = 0;
  CompareSettings submittedCompare_;
  std::shared_ptr<const FitOutcome> shown_, shownCompare_;
  std::uint64_t shownVersion_ = 0;
  std::string lastFitError_;
  double lastFitWallMs_ = 1e9;  // wall time of the last finished job (main + compare fits)

  // The view image (left / whole) and the compare image (right half).
  SceneViewRenderer renderer_, compareRenderer_;
  SceneViewResult view_, compareView_;
  render::Texture viewTexture_, compareTexture_;
  struct Drawn {
    const FitOutcome* fit = nullptr;
    const FitOutcome* compare = nullptr;
    ViewSpec view;
    int width = 0, height = 0;
    double colourRange = 0;
    ViewQuality quality = ViewQuality::Settled;
    bool compareOn = false;
  };
  std::optional<Drawn> drawn_;
  int interactFrames_ = 1 << 20;  // frames since the last camera / drag gesture (settled after a few)

  // Tools
  int selected_ = -1;
  enum class Drag { None, Orbit, Pan, Sample, NormalTip, PatchHandle, Gizmo, SlicePlane } drag_ = Drag::None;
  PatchHandle patchHandle_;            // the grabbed patch handle
  Vec<3> patchGrabStart_ = Vec<3>::Zero();
  Vec<2> lastMouse_ = Vec<2>::Zero();
  Vec<3> dragPlanePoint_ = Vec<3>::Zero();  // 3D sample drags move on the plane through it facing the camera
  // Slice-plane drags (Alt + left drag): the grabbed point slides on the line through it along
  // the plane's normal; the offset follows the line parameter nearest to the mouse ray.
  struct SliceGrab {
    Vec<3> point = Vec<3>::Zero();  // on the plane, world units
    double offset = 0;              // view.slice.offset at the press
    std::optional<double> lineParameter;  // at the press; none when the normal points along the ray
    double pressY = 0;              // view pixels, for the fallback (vertical mouse motion)
  } sliceGrab_;
  bool prevMouseDown_[3] = {false, false, false};
  std::array<bool, 512> prevKeys_{};
  CameraSpec homeCamera_;
  std::array<double, 2> homeCenter_{0, 0};
  double homeHalfHeight_ = 1.5;
  std::vector<CameraSpec> savedViews_;
  RadiusExplorer explorer_;
  SceneViewRenderer thumbnailRenderer_;
  std::vector<render::Texture> thumbnails_;  // one per explorer entry, in order
  int thumbnailGeneration_ = -1;
  std::string csvPath_ = "diagnostics.csv";
  std::map<std::string, std::array<float, 4>> widgets_;

  bool showPartitionBoxes_ = false;
  double colourRange_ = 0;  // 2D: 0 = automatic
  void drawPartitionBoxes();
  // Panels' text fields
  std::string openPath_, savePath_, exportPath_;
  std::string meshPath_ = "mesh.obj", meshExportPath_ = "filled.glb", zeroSetPath_ = "zero-set.glb";
  std::string pendingScreenshot_;
  bool pendingScreenshotUi_ = true;
  bool screenshotWithUi_ = false;
  int screenshotCounter_ = 0;
  GuiStatus status_;
  bool quit_ = false;
  int width_ = 800, height_ = 600;
  // The view's rectangle in the window (pixels): right of the left panel, above the explorer
  // strip and the status bar; the whole window when the panels are hidden (Tab).
  int viewX_ = 0, viewY_ = 0, viewW_ = 800, viewH_ = 600;
  void layoutView();
};

// Fixed layout (pixels).
inline constexpr float kLeftPanelWidth = 330.0f;
inline constexpr float kStatusBarHeight = 24.0f;
inline constexpr float kExplorerHeight = 200.0f;

}  // namespace hermite::app
