#pragma once
// What the window's parts share: the document, the fits on screen, the view image and its
// rectangle, the selection, the status line and the rectangles of the widgets drawn this frame.
// GuiApp owns one; every panel and tool gets it by reference and keeps its own state besides.

#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/gui/document.h"
#include "app/gui/fit_presenter.h"
#include "app/gui/gui_status.h"
#include "app/gui/view_image.h"
#include "core/base/geometry.h"

namespace hermite::app {

struct GuiOptions {
  bool iniFile = false;             // ImGui's layout file (off in tests)
  bool synchronousFits = false;     // wait for each fit inside the frame (render --ui, tests)
  // The window and its benches: fits run below the GUI's CPU priority (background_priority.h).
  // Off in tests, which share OpenBLAS's pool with later work in the same process.
  bool lowPriorityFits = false;
  std::string screenshotDirectory = ".";
  // Wall-clock figures differ run to run: `render --ui` hides them (same input → same bytes).
  bool showTimings = true;
  // The UI scale at start (type, widgets, layout): --ui-scale, else the monitor's content scale
  // in the window and 1 offscreen. Ctrl + / Ctrl − change it, Ctrl 0 returns to this value.
  float uiScale = 1.0f;
};

// Panels' visibility (`render --ui` shows them all; tests toggle them).
struct PanelVisibility {
  bool data = true, fit = true, compare = false, transform = false, diagnostics = true, view = true, explore = false,
       help = false, messages = false;  // messages: the message log window (F2)
  bool hideUi = false;     // Tab: only the view
  bool presenter = false;  // F5 or view.presenter: panels hidden, a large caption (presenter_caption.h)
};

// The view's rectangle in the window (pixels): right of the left panel, above the explorer strip
// and the status bar; the whole window when the panels are hidden (Tab).
struct ViewRect {
  int x = 0, y = 0, w = 800, h = 600;
  bool split = false;  // the compare view was drawn: the left half is the primary view
  Vec<2> origin() const { return Vec<2>(x, y); }
  // Width of the view that the camera and the 2D view map mouse positions to.
  int primaryWidth() const { return split ? w / 2 : w; }
};

// The camera that Home returns to: the one of the scene as opened.
struct CameraHome {
  CameraSpec camera;
  std::array<double, 2> center{0, 0};
  double halfHeight = 1.5;
};

// The mouse gesture in progress (it owns the mouse until release).
enum class Drag { None, Orbit, Pan, Sample, NormalTip, PatchHandle, Gizmo, SlicePlane };

struct GuiContext {
  GuiContext(Document doc, GuiOptions opts);

  Document document;
  GuiOptions options;
  GuiStatus status;
  PanelVisibility panels;
  CompareSettings compare;
  ViewRect view;
  CameraHome home;
  FitPresenter fits;
  ViewImage image;
  int selected = -1;  // the selected sample, −1 for none
  Drag drag = Drag::None;
  bool showGizmo = false;
  bool showPartitionBoxes = false;
  double colourRange = 0;  // 2D heat map: 0 = automatic
  std::string savePath;    // the path Save writes (the Data panel's field, Ctrl+S)
  // What the last opened data file held (the Data panel describes it while its fit runs).
  struct LoadedData {
    DataSpec data;  // the scene's data it describes
    int samples = 0;
    double spacing = 0;
    std::vector<std::string> warnings;
    // The samples' positions (Dim × N), drawn until a fit of this data is shown (loaded_points_overlay.h).
    std::shared_ptr<const Eigen::MatrixXd> points;
  };
  std::optional<LoadedData> loadedData;
  std::map<std::string, std::array<float, 4>> widgets;  // this frame's named widget rectangles
  // A screenshot taken after this frame is drawn: the whole window (withUi) or the view image.
  struct ScreenshotRequest {
    std::string path;
    bool withUi = true;
  };
  std::optional<ScreenshotRequest> screenshot;
  bool screenshotWithUi = false;  // what F12 and the View panel's button take
  int screenshotCounter = 0;      // their files are numbered
  float uiScale = 1.0f;           // the UI scale now (gui/ui_scale.h); GuiApp rebuilds the fonts when it changes

  // A length of the layout at UI scale 1 in pixels now.
  float px(float pixelsAtScale1) const { return pixelsAtScale1 * uiScale; }

  const Scene& scene() const { return document.scene(); }
  int dimension() const { return scene().dimension(); }
  // The fit on screen when it is of the document's mode (fit_presenter.h), else null.
  const FitOutcome* currentFit() const { return fits.current(scene().mode); }
  void setStatus(std::string message, bool error = false);
  // Records the last ImGui item's rectangle under `name` (how scripted UI tests find widgets).
  void recordWidget(const std::string& name);
  // Home becomes the camera of the document's scene.
  void setHomeFromScene();
  // The next numbered screenshot (hermite-lab-NNN.png in options.screenshotDirectory).
  void requestNumberedScreenshot();
};

// Fixed layout (pixels at UI scale 1; GuiContext::px scales them). The status bar holds two
// lines of text.
inline constexpr float kLeftPanelWidth = 330.0f;
inline constexpr float kStatusBarHeight = 40.0f;
inline constexpr float kExplorerHeight = 200.0f;

}  // namespace hermite::app
