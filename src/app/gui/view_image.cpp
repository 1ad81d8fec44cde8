#include "app/gui/view_image.h"

#include <imgui.h>

#include <algorithm>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <string>

#include "app/gui/gui_context.h"
#include "app/gui/view_legends.h"

namespace hermite::app {

namespace {

// Frames after the last interaction before the view is redrawn at full quality.
constexpr int kSettleFrames = 3;

// A gesture draws the 3D view at 1/d of the view's size per axis: d = 2 (a quarter of the rays),
// larger while the last gesture frame's render took more than kGestureViewBudgetMs, so that a
// frame with its panels stays within about 33 ms on a loaded software rasteriser; smaller again
// (not below 2) when it took less than a third of that.
constexpr double kGestureViewBudgetMs = 15.0;
constexpr int kMaxGestureDivisor = 4;

// `last` is the image on screen; `lastWasGesture` whether it was drawn during a gesture.
int gestureDivisor(const SceneViewResult& last, bool lastWasGesture, int viewWidth) {
  if (!lastWasGesture || last.width <= 0) return 2;
  const int d = std::clamp(int(std::lround(double(viewWidth) / last.width)), 2, kMaxGestureDivisor);
  if (last.ms > kGestureViewBudgetMs) return std::min(d + 1, kMaxGestureDivisor);
  if (last.ms < kGestureViewBudgetMs / 3) return std::max(d - 1, 2);
  return d;
}

ImTextureID textureId(const render::Texture& t) {
  return reinterpret_cast<ImTextureID>(static_cast<std::uintptr_t>(t.id()));
}

// Uploads an image into `texture`, (re)creating it when the size changed. An image shown at its
// own size (`shownW` × `shownH` window pixels) is sampled at its texel centres, where nearest and
// linear filtering give the same bytes; nearest costs a software rasteriser less per pixel. A
// stretched one (a gesture's reduced view) is filtered linearly.
void uploadImage(render::Texture& texture, const ImageRgba8& image, int shownW, int shownH) {
  if (!texture.valid() || texture.width() != image.width || texture.height() != image.height) {
    texture = render::Texture::create2D(GL_RGBA8, image.width, image.height);
    texture.setWrap(GL_CLAMP_TO_EDGE);
  }
  const GLenum filter = image.width == shownW && image.height == shownH ? GL_NEAREST : GL_LINEAR;
  texture.setFilter(filter, filter);
  texture.upload2D(GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
}

}  // namespace

void ViewImage::redrawIfStale(GuiContext& ctx) {
  const auto& shown = ctx.fits.shown();
  if (!shown) return;
  const auto& shownCompare = ctx.fits.shownCompare();
  const bool interacting = ctx.drag != Drag::None || ctx.document.inGesture();
  interactFrames_ = interacting ? 0 : interactFrames_ + 1;
  const ViewQuality quality = interactFrames_ > kSettleFrames ? ViewQuality::Settled : ViewQuality::Interactive;
  const bool split = ctx.compare.enabled && shownCompare && !ctx.panels.hideUi;
  const int viewW = ctx.view.w, viewH = ctx.view.h;
  const int w = split ? std::max(1, viewW / 2) : viewW;
  const Drawn now{shown.get(), split ? shownCompare.get() : nullptr, ctx.scene().view, viewW, viewH,
                  ctx.colourRange, quality, split};
  renderer_.setBackground(!ctx.options.synchronousFits);
  bool arrived = false;
  try {
    arrived = renderer_.adoptFinished();
  } catch (const std::exception& e) {
    ctx.setStatus(std::string("drawing failed: ") + e.what(), true);
  }
  if (!arrived && drawn_ && *drawn_ == now) return;
  renderer_.colourRange = compareRenderer_.colourRange = ctx.colourRange;
  // A drag draws the 3D view at a fraction of the resolution (the texture is stretched).
  const bool reduced = quality == ViewQuality::Interactive && ctx.dimension() == 3;
  const int d = reduced ? gestureDivisor(view_, drawn_ && drawn_->quality == ViewQuality::Interactive, w) : 1;
  const int rw = std::max(1, w / d), rh = std::max(1, viewH / d);
  try {
    // 2D views stay on the GPU (no read-back and re-upload per frame); 3D ones are read back.
    SceneViewResult r = renderer_.render(shown, ctx.scene(), rw, rh, quality, true);
    if (!r.nothingYet) {  // else the image on screen stays until the fit's bake arrives
      view_ = std::move(r);
      if (!view_.gpuImage) uploadImage(viewTexture_, view_.image, w, viewH);
    }
    if (split) {
      compareView_ = compareRenderer_.render(shownCompare, ctx.scene(), rw, rh, quality, true);
      if (!compareView_.gpuImage) uploadImage(compareTexture_, compareView_.image, w, viewH);
    }
  } catch (const std::exception& e) {
    ctx.setStatus(std::string("drawing failed: ") + e.what(), true);
  }
  drawn_ = now;
  ctx.view.split = split;
}

void ViewImage::draw(const GuiContext& ctx) const {
  ImDrawList* bg = ImGui::GetBackgroundDrawList();
  if (!drawn_ || (!view_.gpuImage && !viewTexture_.valid())) return;
  const float x0 = float(ctx.view.x), y0 = float(ctx.view.y), y1 = float(ctx.view.y + ctx.view.h);
  const float w = float(ctx.view.primaryWidth());
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
  if (compareShown) drawCompareLabels(ctx, x0, w);
  drawViewLegends(ctx, view_);
}

// A line between the halves and, at the bottom of each, what it fitted.
void ViewImage::drawCompareLabels(const GuiContext& ctx, float x0, float w) const {
  ImDrawList* bg = ImGui::GetBackgroundDrawList();
  const float y0 = float(ctx.view.y), y1 = float(ctx.view.y + ctx.view.h);
  bg->AddLine(ImVec2(x0 + w, y0), ImVec2(x0 + w, y1), IM_COL32(60, 60, 60, 255), 2.0f);
  const auto label = [&](float x, const FitOutcome* f) {
    if (!f) return;
    const Scene& s = f->scene;
    char text[160];
    const int n = std::snprintf(text, sizeof text, "%s  %s", std::string(fitMethodName(s.fit.method)).c_str(),
                                std::string(kernelName(s.fit.kernel)).c_str());
    if (Kernel{s.fit.kernel, s.fit.radius}.usesRadius() && n > 0 && n < int(sizeof text))
      std::snprintf(text + n, sizeof text - std::size_t(n), "  r = %.4g", s.fit.radius);
    const float font = ImGui::GetFontSize(), pad = 0.4f * font;  // sizes follow the UI scale
    bg->AddRectFilled(ImVec2(x + pad, y1 - 2 * pad - font - pad), ImVec2(x + 3 * pad + ImGui::CalcTextSize(text).x, y1 - pad),
                      IM_COL32(0, 0, 0, 170));
    bg->AddText(ImVec2(x + 2 * pad, y1 - 2 * pad - font), IM_COL32(255, 255, 255, 255), text);
  };
  label(x0, ctx.fits.shown().get());
  label(x0 + w, ctx.fits.shownCompare().get());
}

bool ViewImage::wantsFrame() const {
  return interactFrames_ <= kSettleFrames || renderer_.hasFrameWork() || compareRenderer_.hasFrameWork();
}

ImageRgba8 ViewImage::pixels() const { return view_.gpuImage ? renderer_.readGpuImage() : view_.image; }

}  // namespace hermite::app
