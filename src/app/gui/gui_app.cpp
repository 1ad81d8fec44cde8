#include "app/gui/gui_app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>  // key codes only (FrameInput uses GLFW's numbering)
#include <imgui.h>

#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/base/errors.h"
#include "core/trace/image.h"
#include "io/png_file.h"
#include "render/gl/offscreen.h"
#include "render/legend.h"

namespace hermite::app {

namespace {

// Frames after the last interaction before the view is redrawn at full quality.
constexpr int kSettleFrames = 3;
// A fit expected to take less than this (the last one did) is waited for within the frame that
// submitted it (ms).
constexpr double kSameFrameFitMs = 12.0;

ImTextureID textureId(const render::Texture& t) {
  return reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(t.id()));
}

// Uploads an image into `texture`, (re)creating it when the size changed.
void uploadImage(render::Texture& texture, const ImageRgba8& image) {
  if (!texture.valid() || texture.width() != image.width || texture.height() != image.height) {
    texture = render::Texture::create2D(GL_RGBA8, image.width, image.height);
    texture.setFilter(GL_LINEAR, GL_LINEAR);
    texture.setWrap(GL_CLAMP_TO_EDGE);
  }
  texture.upload2D(GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
}

}  // namespace

GuiApp::GuiApp(Document document, GuiOptions options)
    : document_(std::move(document)), options_(std::move(options)) {
  imgui_ = ImGui::CreateContext();
  ImGuiIO& io = ImGui::GetIO();
  if (!options_.iniFile) io.IniFilename = nullptr;
  io.LogFilename = nullptr;
  // ImGui 1.86 reads keys through KeyMap indices into KeysDown: we index by GLFW key code.
  io.KeyMap[ImGuiKey_Tab] = GLFW_KEY_TAB;
  io.KeyMap[ImGuiKey_LeftArrow] = GLFW_KEY_LEFT;
  io.KeyMap[ImGuiKey_RightArrow] = GLFW_KEY_RIGHT;
  io.KeyMap[ImGuiKey_UpArrow] = GLFW_KEY_UP;
  io.KeyMap[ImGuiKey_DownArrow] = GLFW_KEY_DOWN;
  io.KeyMap[ImGuiKey_PageUp] = GLFW_KEY_PAGE_UP;
  io.KeyMap[ImGuiKey_PageDown] = GLFW_KEY_PAGE_DOWN;
  io.KeyMap[ImGuiKey_Home] = GLFW_KEY_HOME;
  io.KeyMap[ImGuiKey_End] = GLFW_KEY_END;
  io.KeyMap[ImGuiKey_Insert] = GLFW_KEY_INSERT;
  io.KeyMap[ImGuiKey_Delete] = GLFW_KEY_DELETE;
  io.KeyMap[ImGuiKey_Backspace] = GLFW_KEY_BACKSPACE;
  io.KeyMap[ImGuiKey_Space] = GLFW_KEY_SPACE;
  io.KeyMap[ImGuiKey_Enter] = GLFW_KEY_ENTER;
  io.KeyMap[ImGuiKey_Escape] = GLFW_KEY_ESCAPE;
  io.KeyMap[ImGuiKey_KeyPadEnter] = GLFW_KEY_KP_ENTER;
  io.KeyMap[ImGuiKey_A] = GLFW_KEY_A;
  io.KeyMap[ImGuiKey_C] = GLFW_KEY_C;
  io.KeyMap[ImGuiKey_V] = GLFW_KEY_V;
  io.KeyMap[ImGuiKey_X] = GLFW_KEY_X;
  io.KeyMap[ImGuiKey_Y] = GLFW_KEY_Y;
  io.KeyMap[ImGuiKey_Z] = GLFW_KEY_Z;
  ImGui::StyleColorsDark();
  ImGui::GetStyle().WindowRounding = 3.0f;
  imguiRenderer_ = std::make_unique<render::ImGuiRenderer>();

  const Scene& s = document_.scene();
  homeCamera_ = s.view.camera;
  homeCenter_ = s.view.center2d;
  homeHalfHeight_ = s.view.halfHeight2d;
  savePath_ = document_.path().empty() ? "scene.json" : document_.path();
  openPath_ = document_.path();
  exportPath_ = s.dimension() == 2 ? "samples.xyn" : "samples.xyzn";
  if (s.fit.radius > 0) {
    explorer_.lower = s.fit.radius / 10;
    explorer_.upper = s.fit.radius * 3;
  }
}

GuiApp::~GuiApp() {
  explorer_.cancel();
  // The GL objects (textures, renderers) are released by their members; ImGui last.
  imguiRenderer_.reset();
  ImGui::DestroyContext(imgui_);
}

void GuiApp::setStatus(std::string message, bool error) {
  status_.message = std::move(message);
  status_.error = error;
}

void GuiApp::feedImGui(const FrameInput& in) {
  ImGui::SetCurrentContext(imgui_);
  ImGuiIO& io = ImGui::GetIO();
  io.DisplaySize = ImVec2(float(in.width), float(in.height));
  io.DisplayFramebufferScale = ImVec2(1, 1);
  io.DeltaTime = float(std::max(in.deltaSeconds, 1e-4));
  io.MousePos = in.mouseX >= 0 ? ImVec2(float(in.mouseX), float(in.mouseY)) : ImVec2(-FLT_MAX, -FLT_MAX);
  for (int b = 0; b < 3; ++b) io.MouseDown[b] = in.mouseDown[b];
  io.MouseWheel = in.wheel;
  for (int k = 0; k < 512; ++k) io.KeysDown[k] = in.keysDown[k];
  io.KeyCtrl = in.ctrl;
  io.KeyShift = in.shift;
  io.KeyAlt = in.alt;
  for (unsigned c : in.characters) io.AddInputCharacter(c);
}

std::optional<Scene> GuiApp::compareScene(const Scene& s) const {
  if (!compare.enabled || (s.mode != SceneMode::Implicit2d && s.mode != SceneMode::Implicit3d)) return std::nullopt;
  Scene c = s;
  switch (compare.with) {
    case CompareWith::RbfOffset: c.fit.method = FitMethod::RbfOffset; break;
    case CompareWith::Hrbf: c.fit.method = FitMethod::Hrbf; break;
    case CompareWith::OtherKernel: c.fit.kernel = compare.kernel; break;
    case CompareWith::OtherRadius: c.fit.radius = compare.radius; break;
  }
  return c;
}

void GuiApp::submitIfStale() {
  const bool compareChanged = compare.enabled != submittedCompare_.enabled ||
                              (compare.enabled && (compare.with != submittedCompare_.with ||
                                                   compare.kernel != submittedCompare_.kernel ||
                                                   compare.radius != submittedCompare_.radius));
  if (document_.version() == submittedVersion_ && !compareChanged) return;
  submittedVersion_ = document_.version();
  submittedCompare_ = compare;
  worker_.submit(scene(), submittedVersion_, compareScene(scene()));
  if (options_.synchronousFits)
    worker_.waitIdle(600);
  else if (lastFitWallMs_ < kSameFrameFitMs)
    // Fits as quick as the last one (a drag's bordered refits) show in this very frame: one
    // short wait instead of a frame of latency. Slower ones stay on the worker.
    worker_.waitIdle(kSameFrameFitMs / 1000.0);
}

void GuiApp::adoptFinishedFits() {
  std::optional<FitJobResult> r = worker_.poll();
  if (!r) return;
  lastFitWallMs_ = r->main->wallMs + (r->compare ? r->compare->wallMs : 0.0);
  if (r->main->ok()) {
    shown_ = r->main;
    shownVersion_ = r->version;
    lastFitError_.clear();
  } else {
    // Keep the last good model on screen and say why the new one is not there.
    lastFitError_ = r->main->error;
    setStatus("fit failed: " + r->main->error, true);
  }
  shownCompare_ = r->compare && r->compare->ok() ? r->compare : nullptr;
  if (r->compare && !r->compare->ok()) setStatus("compare fit failed: " + r->compare->error, true);
}

void GuiApp::layoutView() {
  const bool side = !panels.hideUi && width_ > int(kLeftPanelWidth) + 64;
  viewX_ = side ? int(kLeftPanelWidth) : 0;
  viewY_ = 0;
  viewW_ = std::max(1, width_ - viewX_);
  const int below = panels.hideUi ? 0 : int(kStatusBarHeight) + (panels.explore ? int(kExplorerHeight) : 0);
  viewH_ = std::max(1, height_ - below);
}

void GuiApp::redrawViewIfStale() {
  if (!shown_) return;
  const bool interacting = drag_ != Drag::None || document_.inGesture();
  interactFrames_ = interacting ? 0 : interactFrames_ + 1;
  const ViewQuality quality = interactFrames_ > kSettleFrames ? ViewQuality::Settled : ViewQuality::Interactive;
  const bool split = compare.enabled && shownCompare_ && !panels.hideUi;
  const int w = split ? std::max(1, viewW_ / 2) : viewW_;
  Drawn now{shown_.get(), split ? shownCompare_.get() : nullptr, scene().view, viewW_, viewH_, colourRange_, quality, split};
  if (drawn_ && drawn_->fit == now.fit && drawn_->compare == now.compare && drawn_->view == now.view &&
      drawn_->width == now.width && drawn_->height == now.height && drawn_->quality == now.quality &&
      drawn_->compareOn == now.compareOn && drawn_->colourRange == now.colourRange)
    return;
  renderer_.colourRange = compareRenderer_.colourRange = colourRange_;
  // A drag draws the 3D view at half resolution (the texture is stretched): ~4× fewer rays.
  const bool half = quality == ViewQuality::Interactive && dimension() == 3;
  const int rw = half ? std::max(1, w / 2) : w, rh = half ? std::max(1, viewH_ / 2) : viewH_;
  try {
    // 2D views stay on the GPU (no read-back and re-upload per frame); 3D ones are read back.
    view_ = renderer_.render(shown_, scene(), rw, rh, quality, true);
    if (!view_.gpuImage) uploadImage(viewTexture_, view_.image);
    if (split) {
      compareView_ = compareRenderer_.render(shownCompare_, scene(), rw, rh, quality, true);
      if (!compareView_.gpuImage) uploadImage(compareTexture_, compareView_.image);
    }
  } catch (const std::exception& e) {
    setStatus(std::string("drawing failed: ") + e.what(), true);
  }
  drawn_ = now;
}

void GuiApp::drawViewImage() {
  ImDrawList* bg = ImGui::GetBackgroundDrawList();
  if (!drawn_ || (!view_.gpuImage && !viewTexture_.valid())) return;
  const float x0 = float(viewX_), y0 = float(viewY_), y1 = float(viewY_ + viewH_);
  const float w = float(primaryViewWidth());
  // A GPU-kept view has GL rows bottom-up: flip v.
  auto addView = [&](const SceneViewResult& r, const render::Texture& uploaded, float left) {
    if (r.gpuImage)
      bg->AddImage(textureId(*r.gpuImage), ImVec2(left, y0), ImVec2(left + w, y1), ImVec2(0, 1), ImVec2(1, 0));
    else
      bg->AddImage(textureId(uploaded), ImVec2(left, y0), ImVec2(left + w, y1));
  };
  // The view images are opaque: drawn without blending (a blended full-view quad reads the
  // framebuffer back, which software rasterisers pay for every frame), then ImGui's state again.
  bg->AddCallback([](const ImDrawList*, const ImDrawCmd*) { glDisable(GL_BLEND); }, nullptr);
  addView(view_, viewTexture_, x0);
  const bool compareShown = drawn_->compareOn && (compareView_.gpuImage || compareTexture_.valid());
  if (compareShown) addView(compareView_, compareTexture_, x0 + w);
  bg->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
  if (compareShown) {
    bg->AddLine(ImVec2(x0 + w, y0), ImVec2(x0 + w, y1), IM_COL32(60, 60, 60, 255), 2.0f);
    const auto label = [&](float x, const FitOutcome* f) {
      if (!f) return;
      const Scene& s = f->scene;
      char text[160];
      std::snprintf(text, sizeof text, "%s  %s%s", std::string(fitMethodName(s.fit.method)).c_str(),
                    std::string(kernelName(s.fit.kernel)).c_str(),
                    Kernel{s.fit.kernel, s.fit.radius}.usesRadius() ? ("  r = " + std::to_string(s.fit.radius)).c_str() : "");
      bg->AddRectFilled(ImVec2(x + 4, y1 - 26), ImVec2(x + 8 + ImGui::CalcTextSize(text).x + 6, y1 - 6),
                        IM_COL32(0, 0, 0, 170));
      bg->AddText(ImVec2(x + 9, y1 - 24), IM_COL32(255, 255, 255, 255), text);
    };
    label(x0, shown_.get());
    label(x0 + w, shownCompare_.get());
  }
  if (dimension() == 2 && view_.colourRange > 0) {
    render::LegendOptions legend;
    legend.range = view_.colourRange;
    legend.isoSpacing = view_.isoSpacing;
    legend.cornerX = float(viewX_ + primaryViewWidth());
    legend.cornerY = float(viewY_ + viewH_);
    render::drawColorLegend(bg, legend);
  }
}

// The partition-of-unity leaves (their boxes: supports shrunk by their factor), in the model's
// frame mapped to the world, projected into the view as ImGui lines.
void GuiApp::drawPartitionBoxes() {
  const FitOutcome* f = shown_.get();
  if (!f) return;
  ImDrawList* dl = ImGui::GetBackgroundDrawList();
  const ImU32 colour = IM_COL32(90, 60, 160, 170);
  const Vec<2> o = viewOrigin();
  constexpr std::size_t kMaxBoxes = 4000;  // beyond this the lines only hide the view
  if (f->fit2 && f->fit2->pu) {
    const auto& pu = *f->fit2->pu;
    const View2d view = sceneView2d(scene(), primaryViewWidth(), viewH_);
    for (std::size_t k = 0; k < std::min(pu.leaves().size(), kMaxBoxes); ++k) {
      const auto& leaf = pu.leaves()[k];
      const Vec<2> c = leaf.support.center(), h = 0.5 * leaf.support.extent() / leaf.factor;
      ImVec2 pts[4];
      const Vec<2> corners[4] = {c + Vec<2>(-h.x(), -h.y()), c + Vec<2>(h.x(), -h.y()), c + Vec<2>(h.x(), h.y()),
                                 c + Vec<2>(-h.x(), h.y())};
      for (int i = 0; i < 4; ++i) {
        const Vec<2> q = view.worldToPixel(pu.frame().apply(corners[i])) + o;
        pts[i] = ImVec2(float(q.x()), float(q.y()));
      }
      dl->AddPolyline(pts, 4, colour, ImDrawFlags_Closed, 1.0f);
    }
  } else if (f->fit3 && f->fit3->pu) {
    const auto& pu = *f->fit3->pu;
    const Camera cam = sceneCamera(scene(), primaryViewWidth(), viewH_);
    for (std::size_t k = 0; k < std::min(pu.leaves().size(), kMaxBoxes); ++k) {
      const auto& leaf = pu.leaves()[k];
      const Vec<3> c = leaf.support.center(), h = 0.5 * leaf.support.extent() / leaf.factor;
      const auto corner = [&](int i) {
        return pu.frame().apply(Vec<3>(c.x() + ((i & 1) ? h.x() : -h.x()), c.y() + ((i & 2) ? h.y() : -h.y()),
                                       c.z() + ((i & 4) ? h.z() : -h.z())));
      };
      for (int i = 0; i < 8; ++i)
        for (int bit = 1; bit <= 4; bit <<= 1) {
          if (i & bit) continue;
          const Vec<3> a = corner(i), b = corner(i | bit);
          if (cam.projection() == Projection::Perspective &&
              ((a - cam.eye()).dot(cam.forward()) <= 0 || (b - cam.eye()).dot(cam.forward()) <= 0))
            continue;
          const Vec<2> pa = cam.project(a) + o, pb = cam.project(b) + o;
          dl->AddLine(ImVec2(float(pa.x()), float(pa.y())), ImVec2(float(pb.x()), float(pb.y())), colour, 1.0f);
        }
    }
  }
}

void GuiApp::requestScreenshot(const std::string& path, bool withUi) {
  pendingScreenshot_ = path;
  pendingScreenshotUi_ = withUi;
}

void GuiApp::screenshotNow(const std::string& path, bool withUi, const FrameInput& in) {
  try {
    ImageRgba8 image;
    if (withUi) {
      // Read back what was just drawn: the whole frame with its panels.
      render::OffscreenTarget target(in.width, in.height, false);
      target.bind();
      renderFrame();
      image = target.read();
      glBindFramebuffer(GL_FRAMEBUFFER, 0);
    } else {
      image = view_.gpuImage ? renderer_.readGpuImage() : view_.image;
    }
    writePng(path, image);
    setStatus("saved screenshot " + path);
  } catch (const std::exception& e) {
    setStatus(std::string("screenshot failed: ") + e.what(), true);
  }
}

// The window's pixels: the background colour by a clear, then ImGui's draw lists (the view image,
// overlays, panels). The background is not an ImGui rectangle: a full-window blended quad is a
// large share of a frame on llvmpipe, a clear is nearly free. The clear colour is
// ImGui's own 8-bit rounding of the colour (IM_F32_TO_INT8_SAT) over 255, so the bytes are those
// the rectangle gave.
void GuiApp::renderFrame() {
  const auto& b = scene().view.background;
  const ImU32 c = ImGui::GetColorU32(ImVec4(float(b[0]), float(b[1]), float(b[2]), 1.0f));
  glClearColor(float((c >> IM_COL32_R_SHIFT) & 0xFF) / 255.0f, float((c >> IM_COL32_G_SHIFT) & 0xFF) / 255.0f,
               float((c >> IM_COL32_B_SHIFT) & 0xFF) / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  imguiRenderer_->render(ImGui::GetDrawData());
}

void GuiApp::takePendingScreenshot(const FrameInput& in) {
  if (pendingScreenshot_.empty()) return;
  const std::string path = std::move(pendingScreenshot_);
  pendingScreenshot_.clear();
  screenshotNow(path, pendingScreenshotUi_, in);
}

void GuiApp::frame(const FrameInput& in) {
  width_ = in.width;
  height_ = in.height;
  layoutView();
  feedImGui(in);
  ImGui::NewFrame();
  adoptFinishedFits();
  handleDroppedFiles(in);
  handleShortcuts(in);
  handleViewInput(in);
  if (!panels.hideUi) drawPanels();
  submitIfStale();
  adoptFinishedFits();  // synchronous fits (and fast ones) show in this very frame
  redrawViewIfStale();
  drawViewImage();
  drawSelectionOverlay();
  drawPatchHandles();
  drawHoleLabels();
  if (showPartitionBoxes_) drawPartitionBoxes();
  if (showGizmo_ && (scene().mode == SceneMode::Implicit2d || scene().mode == SceneMode::Implicit3d)) drawGizmo();
  if (panels.help) drawHelpOverlay();
  if (!panels.hideUi) drawStatusBar();
  ImGui::Render();

  GLint framebuffer = 0;
  glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
  glViewport(0, 0, in.width, in.height);
  renderFrame();
  if (!pendingScreenshot_.empty()) {
    takePendingScreenshot(in);
    glBindFramebuffer(GL_FRAMEBUFFER, GLuint(framebuffer));
    glViewport(0, 0, in.width, in.height);
  }
  for (int b = 0; b < 3; ++b) prevMouseDown_[b] = in.mouseDown[b];
  prevKeys_ = in.keysDown;
}

}  // namespace hermite::app
