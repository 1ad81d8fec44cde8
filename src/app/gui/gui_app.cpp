#include "app/gui/gui_app.h"

#include "app/gui/background_priority.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes only (FrameInput uses GLFW's numbering)
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <type_traits>

#include "app/gui/axes_overlay.h"
#include "app/gui/document_actions.h"
#include "app/gui/gui_widgets.h"
#include "app/gui/loaded_points_overlay.h"
#include "app/gui/partition_box_overlay.h"
#include "app/gui/ui_scale.h"
#include "app/panels/help_overlay.h"
#include "app/panels/message_log.h"
#include "app/panels/presenter_caption.h"
#include "app/panels/status_bar.h"
#include "core/trace/image.h"
#include "io/png_file.h"
#include "render/gl/offscreen.h"
#include "render/glyph_misses.h"

namespace hermite::app {

namespace {

// Vertices and draw commands of a frame's ImGui draw data.
void countDrawData(const ImDrawData& data, int& vertices, int& commands) {
  vertices = data.TotalVtxCount;
  commands = 0;
  for (int i = 0; i < data.CmdListsCount; ++i) commands += data.CmdLists[i]->CmdBuffer.Size;
}

// How far (view pixels) the mouse may move between press and release of a click.
constexpr double kClickSlopPx = 3.0;

// The view's rectangle: right of the left panel, above the explorer strip and the status bar;
// the whole window when the panels are hidden (Tab, presenter mode).
void layoutView(GuiContext& ctx, int width, int height) {
  const PanelVisibility& panels = ctx.panels;
  const bool hidden = panels.hideUi || panels.presenter;
  const int panelWidth = int(ctx.px(kLeftPanelWidth));
  const bool side = !hidden && width > panelWidth + 64;
  ViewRect& view = ctx.view;
  view.x = side ? panelWidth : 0;
  view.y = 0;
  view.w = std::max(1, width - view.x);
  const int below = hidden ? 0 : int(ctx.px(kStatusBarHeight)) + (panels.explore ? int(ctx.px(kExplorerHeight)) : 0);
  view.h = std::max(1, height - below);
}

}  // namespace

GuiApp::GuiApp(Document document, GuiOptions options) : ctx_(std::move(document), std::move(options)) {
  imgui_ = ImGui::CreateContext();
  // CreateContext makes the new context current only when none is: with another app alive (two
  // windows, tests) the fonts below would go to that app's atlas.
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  if (!ctx_.options.iniFile) io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  mapImGuiKeys();
  fonts_ = render::loadUiFonts(ctx_.uiScale);
  applyUiStyle(ctx_.uiScale);
  imguiRenderer_ = std::make_unique<render::ImGuiRenderer>();
  if (ctx_.options.lowPriorityFits && !ctx_.options.synchronousFits) {
    const FitPriority p = windowFitPriority();
    worker().setBackgroundPriority(p.nice, p.threads, p.idle);
  }
}

void GuiApp::applyUiScale() {
  if (fonts_.scale == ctx_.uiScale) return;
  fonts_ = render::loadUiFonts(ctx_.uiScale);
  applyUiStyle(ctx_.uiScale);
  imguiRenderer_->rebuildFontTexture();
}

GuiApp::~GuiApp() {
  explore_.explorer().cancel();
  // The GL objects (textures, renderers) are released by their members; ImGui last.
  imguiRenderer_.reset();
  ImGui::DestroyContext(imgui_);
}

std::string GuiApp::presenterCaption() const { return app::presenterCaption(ctx_); }

std::optional<std::array<float, 4>> GuiApp::widgetRect(const std::string& name) const {
  const auto it = ctx_.widgets.find(name);
  if (it == ctx_.widgets.end()) return std::nullopt;
  return it->second;
}

bool GuiApp::busy() { return worker().busy() || viewPending() || explorer().running() || data_.exporting(); }

void GuiApp::frame(const FrameInput& in) {
  FramePhaseTimer timer(phases_);
  ImGui::SetCurrentContext(imgui_);
  applyUiScale();
  layoutView(ctx_, in.width, in.height);
  feedImGui(in);
  ImGui::NewFrame();
  timer.mark(FramePhase::Input);
  ctx_.fits.adoptFinished(ctx_.status);
  timer.mark(FramePhase::AdoptFit);
  if (!in.droppedFiles.empty()) openFile(ctx_, in.droppedFiles.front());
  handleShortcuts(in);
  handleViewInput(in);
  timer.mark(FramePhase::Input);
  if (!ctx_.panels.hideUi && !ctx_.panels.presenter) drawPanels();
  timer.mark(FramePhase::Panels);
  ctx_.fits.submitIfStale(ctx_.scene(), ctx_.document.version(), ctx_.document.versions().fitInputs(), ctx_.compare,
                          ctx_.options.synchronousFits);
  timer.mark(FramePhase::Submit);
  ctx_.fits.adoptFinished(ctx_.status);  // synchronous fits (and fast ones) show in this very frame
  timer.mark(FramePhase::AdoptFit);
  ctx_.image.redrawIfStale(ctx_);
  ctx_.image.draw(ctx_);
  timer.mark(FramePhase::View);
  drawLoadedPoints(ctx_);
  drawOverlays();
  timer.mark(FramePhase::Overlays);
  ImGui::Render();
  glyphMisses_ += render::countFallbackGlyphs(*ImGui::GetDrawData());
  countDrawData(*ImGui::GetDrawData(), drawVertices_, drawCommands_);

  GLint framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  glViewport(0, 0, in.width, in.height);
  renderFrame();
  timer.mark(FramePhase::Render);
  if (ctx_.screenshot) {
    takeScreenshot(in);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer));
    glViewport(0, 0, in.width, in.height);
  }
  prevMouseDown_ = in.mouseDown;
  prevKeys_ = in.keysDown;
  framedVersion_ = ctx_.document.version();
}

// What is drawn over the view image: the selection, patch handles, hole labels, partition
// boxes, the gizmo; then the help window and the status bar.
void GuiApp::drawOverlays() {
  samples_.drawSelection();
  recordSampleMarks();
  patch_.drawHandles();
  holeFill_.drawLabels();
  if (ctx_.showPartitionBoxes) drawPartitionBoxes(ctx_);
  drawAxesGizmo(ctx_);
  const SceneMode mode = ctx_.scene().mode;
  if (ctx_.showGizmo && (mode == SceneMode::Implicit2d || mode == SceneMode::Implicit3d)) gizmo_.draw();
  if (ctx_.panels.presenter) drawPresenterCaption(ctx_, fonts_.large);
  if (ctx_.panels.help) drawHelpOverlay(ctx_);
  if (ctx_.panels.messages) drawMessageLog(ctx_);
  if (!ctx_.panels.hideUi && !ctx_.panels.presenter) drawStatusBar(ctx_);
}

// The screen positions of a small cloud's samples, as 6-pixel widget rectangles
// "view.sample.K" (window pixels): how the window tests click a sample.
void GuiApp::recordSampleMarks() {
  constexpr int kMarkedSamples = 16;
  const FitOutcome* fit = ctx_.currentFit();
  const int n = fit ? fit->dataCount() : 0;
  if (n > kMarkedSamples) return;
  for (int k = 0; k < n; ++k) {
    const std::string name = "view.sample." + std::to_string(k);
    const std::optional<Vec<2>> p = samples_.samplePosition(k);
    if (!p) {
      ctx_.widgets.erase(name);
      continue;
    }
    const float x = float(p->x() + ctx_.view.x), y = float(p->y() + ctx_.view.y);
    ctx_.widgets[name] = {x - 3, y - 3, x + 3, y + 3};
  }
}

void GuiApp::drawPanels() {
  ctx_.widgets.clear();
  const ImGuiIO& io = ImGui::GetIO();
  const float bottom = io.DisplaySize.y - ctx_.px(kStatusBarHeight);
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(std::min(ctx_.px(kLeftPanelWidth), io.DisplaySize.x), std::max(50.0f, bottom)),
                           ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(0.90f);
  if (ImGui::Begin("Hermite Lab", nullptr,
                   ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                       ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing)) {
    ImGui::PushItemWidth(-ctx_.px(110.0f));
    if (ctx_.scene().mode == SceneMode::Implicit2d || ctx_.scene().mode == SceneMode::Implicit3d) {
      // The r explorer's toolbar button (shortcut E): highlighted while the strip is open.
      if (ctx_.panels.explore) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyleColorVec4(ImGuiCol_ButtonActive));
      const bool pressed = ImGui::Button("r explorer (E)");
      if (ctx_.panels.explore) ImGui::PopStyleColor();
      if (pressed) ctx_.panels.explore = !ctx_.panels.explore;
    }
    if (ctx_.scene().mode == SceneMode::Patch || ctx_.scene().mode == SceneMode::HoleFill) {
      ImGui::SetNextItemOpen(true, ImGuiCond_Once);
      if (ctx_.scene().mode == SceneMode::Patch) {
        if (ImGui::CollapsingHeader("Patch")) patch_.drawPanel();
      } else if (ImGui::CollapsingHeader("Hole filling")) {
        holeFill_.draw();
      }
      inputText("##save", ctx_.savePath);
      ImGui::SameLine();
      if (ImGui::Button("Save scene")) saveScene(ctx_, ctx_.savePath);
    } else {
      ImGui::SetNextItemOpen(ctx_.panels.data, ImGuiCond_Once);
      if (ImGui::CollapsingHeader("Data")) data_.draw();
      ImGui::SetNextItemOpen(ctx_.panels.fit, ImGuiCond_Once);
      if (ImGui::CollapsingHeader("Fit")) drawFitPanel(ctx_);
      ImGui::SetNextItemOpen(ctx_.panels.compare, ImGuiCond_Once);
      if (ImGui::CollapsingHeader("Compare")) drawComparePanel(ctx_);
      ImGui::SetNextItemOpen(ctx_.panels.transform, ImGuiCond_Once);
      if (ImGui::CollapsingHeader("Transform")) drawTransformPanel(ctx_);
    }
    ImGui::SetNextItemOpen(ctx_.panels.view, ImGuiCond_Once);
    if (ImGui::CollapsingHeader("View")) view_.draw();
    ImGui::Checkbox("Help (F1)", &ctx_.panels.help);
    ImGui::SameLine();
    ImGui::Checkbox("Messages (F2)", &ctx_.panels.messages);
    ctx_.recordWidget("panel.messages");
    ImGui::PopItemWidth();
  }
  ImGui::End();
  if (ctx_.panels.diagnostics) drawDiagnosticsPanel(ctx_);
  if (ctx_.panels.explore && (ctx_.scene().mode == SceneMode::Implicit2d || ctx_.scene().mode == SceneMode::Implicit3d))
    explore_.draw();
}

// Ctrl + (= or keypad +), Ctrl − and Ctrl 0: the UI scale up, down and back to its start value.
void GuiApp::handleScaleKeys(const FrameInput& in) {
  const auto& prev = prevKeys_;
  if (!in.ctrl) return;
  if (keyPressed(in, prev, GLFW_KEY_EQUAL) || keyPressed(in, prev, GLFW_KEY_KP_ADD))
    ctx_.uiScale = stepUiScale(ctx_.uiScale, 1);
  else if (keyPressed(in, prev, GLFW_KEY_MINUS) || keyPressed(in, prev, GLFW_KEY_KP_SUBTRACT))
    ctx_.uiScale = stepUiScale(ctx_.uiScale, -1);
  else if (keyPressed(in, prev, GLFW_KEY_0) || keyPressed(in, prev, GLFW_KEY_KP_0))
    ctx_.uiScale = clampUiScale(ctx_.options.uiScale);
}

void GuiApp::handleShortcuts(const FrameInput& in) {
  const ImGuiIO& io = ImGui::GetIO();
  handleScaleKeys(in);
  if (io.WantTextInput) return;
  const auto& prev = prevKeys_;
  if (in.ctrl && keyPressed(in, prev, GLFW_KEY_Z)) {
    if (in.shift) {
      if (ctx_.document.canRedo()) ctx_.setStatus("redo: " + ctx_.document.redoLabel());
      ctx_.document.redo();
    } else {
      if (ctx_.document.canUndo()) ctx_.setStatus("undo: " + ctx_.document.undoLabel());
      ctx_.document.undo();
    }
    return;
  }
  if (in.ctrl && keyPressed(in, prev, GLFW_KEY_Y)) {
    if (ctx_.document.canRedo()) ctx_.setStatus("redo: " + ctx_.document.redoLabel());
    ctx_.document.redo();
    return;
  }
  if (in.ctrl && keyPressed(in, prev, GLFW_KEY_S)) {
    saveScene(ctx_, ctx_.savePath);
    return;
  }
  if (in.ctrl && keyPressed(in, prev, GLFW_KEY_Q)) quit_ = true;
  if (keyPressed(in, prev, GLFW_KEY_F1) || (keyPressed(in, prev, GLFW_KEY_SLASH) && in.shift)) ctx_.panels.help = !ctx_.panels.help;
  if (keyPressed(in, prev, GLFW_KEY_F2)) ctx_.panels.messages = !ctx_.panels.messages;
  if (keyPressed(in, prev, GLFW_KEY_F5)) ctx_.panels.presenter = !ctx_.panels.presenter;
  if (io.WantCaptureKeyboard) return;
  if (keyPressed(in, prev, GLFW_KEY_F)) camera_.fitToView();
  if (keyPressed(in, prev, GLFW_KEY_E)) ctx_.panels.explore = !ctx_.panels.explore;
  if (keyPressed(in, prev, GLFW_KEY_HOME)) camera_.resetView();
  if (keyPressed(in, prev, GLFW_KEY_N)) samples_.flipSelected();
  if (keyPressed(in, prev, GLFW_KEY_DELETE) || keyPressed(in, prev, GLFW_KEY_BACKSPACE)) samples_.deleteSelected();
  if (keyPressed(in, prev, GLFW_KEY_TAB)) ctx_.panels.hideUi = !ctx_.panels.hideUi;
  if (keyPressed(in, prev, GLFW_KEY_ESCAPE)) ctx_.selected = -1;
  if (keyPressed(in, prev, GLFW_KEY_F12)) ctx_.requestNumberedScreenshot();
}


void GuiApp::handleViewInput(const FrameInput& in) {
  const ImGuiIO& io = ImGui::GetIO();
  const Vec<2> mouse(in.mouseX - ctx_.view.x, in.mouseY - ctx_.view.y);  // view pixels
  const Vec<2> delta = mouse - lastMouse_;
  lastMouse_ = mouse;
  const bool anyDown = in.mouseDown[0] || in.mouseDown[1] || in.mouseDown[2];
  // A drag in progress owns the mouse until release, even over a panel.
  if (ctx_.drag != Drag::None) {
    if (!anyDown) {
      if (ctx_.drag != Drag::Orbit && ctx_.drag != Drag::Pan) ctx_.document.end();
      if (click_) ctx_.selected = click_->sample;  // a press and release in place: a click selects
      click_.reset();
      ctx_.drag = Drag::None;
      return;
    }
    if (click_ && (mouse - click_->at).norm() <= kClickSlopPx) return;  // not yet a drag
    click_.reset();
    switch (ctx_.drag) {
      case Drag::Orbit: camera_.orbit(delta.x(), delta.y()); break;
      case Drag::Pan: camera_.pan(delta.x(), delta.y()); break;
      case Drag::Sample:
      case Drag::NormalTip: samples_.drag(mouse); break;
      case Drag::PatchHandle: patch_.drag(mouse, in); break;
      case Drag::Gizmo: gizmo_.drag(mouse); break;
      case Drag::SlicePlane: slicePlane_.drag(mouse); break;
      case Drag::None: break;
    }
    return;
  }
  if (io.WantCaptureMouse || in.mouseX < 0) return;
  if (mouse.x() < 0 || mouse.y() < 0 || mouse.x() >= ctx_.view.w || mouse.y() >= ctx_.view.h) return;
  if (in.wheel != 0) camera_.zoom(in.wheel, mouse);
  pressInView(in, mouse);
}

// Which gesture a press starts: in the patch editor a handle (else orbit / pan); else the gizmo,
// the slice plane (Alt), a new sample (Ctrl), a sample or its normal's tip, else orbit (3D) or
// pan (2D); Shift + left, right and middle pan.
void GuiApp::pressInView(const FrameInput& in, const Vec<2>& mouse) {
  const bool leftPressed = in.mouseDown[0] && !prevMouseDown_[0];
  if (leftPressed && ctx_.scene().mode == SceneMode::Patch) {
    ctx_.drag = !in.shift && patch_.press(mouse) ? Drag::PatchHandle : in.shift ? Drag::Pan : Drag::Orbit;
    return;
  }
  if (leftPressed && !in.ctrl && !in.shift && ctx_.showGizmo && gizmo_.press(mouse)) {
    ctx_.drag = Drag::Gizmo;
    return;
  }
  if (leftPressed && in.alt && !in.ctrl && slicePlane_.press(mouse)) {
    ctx_.drag = Drag::SlicePlane;
    return;
  }
  if (leftPressed && in.ctrl && !in.shift) {
    samples_.addAt(mouse);
    return;
  }
  if (leftPressed && (!in.shift || in.ctrl)) {
    // The selected sample (or its tip) moves; Ctrl+Shift moves any sample. Anything else orbits
    // (3D) or pans (2D) once the mouse moves, and selects what is under it when it does not.
    if (samples_.press(mouse, in.ctrl && in.shift)) return;
    click_ = Click{mouse, samples_.sampleAt(mouse)};
    ctx_.drag = ctx_.dimension() == 3 ? Drag::Orbit : Drag::Pan;
    return;
  }
  if ((leftPressed && in.shift) || (in.mouseDown[1] && !prevMouseDown_[1]) || (in.mouseDown[2] && !prevMouseDown_[2]))
    ctx_.drag = Drag::Pan;
}

void GuiApp::requestScreenshot(const std::string& path, bool withUi) {
  ctx_.screenshot = GuiContext::ScreenshotRequest{path, withUi};
}

// The pending screenshot: the whole frame just drawn with its panels (read back from a redraw
// into an offscreen target), or the view image alone.
void GuiApp::takeScreenshot(const FrameInput& in) {
  const GuiContext::ScreenshotRequest request = *ctx_.screenshot;
  const std::string& path = request.path;
  ctx_.screenshot.reset();
  try {
    ImageRgba8 image;
    if (request.withUi) {
      render::OffscreenTarget target(in.width, in.height, false);
      target.bind();
      renderFrame();
      image = target.read();
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
    } else {
      image = ctx_.image.pixels();
    }
    writePng(path, image);
    ctx_.setStatus("saved screenshot " + path);
  } catch (const std::exception& e) {
    ctx_.setStatus(std::string("screenshot failed: ") + e.what(), true);
  }
}

// The window's pixels: the background colour by a clear, then ImGui's draw lists (the view image,
// overlays, panels). The background is not an ImGui rectangle: a full-window blended quad is a
// large share of a frame on llvmpipe, a clear is nearly free. The clear colour is
// ImGui's own 8-bit rounding of the colour (IM_F32_TO_INT8_SAT) over 255, so the bytes are those
// the rectangle gave.
void GuiApp::renderFrame() {
  const auto& b = ctx_.scene().view.background;
  const ImU32 c = ImGui::GetColorU32(ImVec4(float(b[0]), float(b[1]), float(b[2]), 1.0f));
  glClearColor(float((c >> IM_COL32_R_SHIFT) & 0xFF) / 255.0f, float((c >> IM_COL32_G_SHIFT) & 0xFF) / 255.0f,
               float((c >> IM_COL32_B_SHIFT) & 0xFF) / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  imguiRenderer_->render(ImGui::GetDrawData());
}


}  // namespace hermite::app
static_assert(!std::is_copy_constructible_v<hermite::app::GuiApp>, "GuiApp parts hold references to its context");
