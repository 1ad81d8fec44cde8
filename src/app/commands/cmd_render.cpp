// `hermite-lab render SCENE -o OUT.png [--size WxH] [--ui [--explore]] [--set KEY=VALUE ...] [--backend osmesa|egl]`
// (docs/cli.md; docs/design.md, Rendering): headless rendering through OSMesa (default) or EGL surfaceless. 2D scenes
// draw the field view with its legend, 3D scenes the implicit tracer (with slice plane and
// overlays as the view says); --ui draws the application's panels on top with ImGui, laid out
// as in the window. Same input → same bytes. Nothing is printed on success.

#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <regex>
#include <string>

#include "app/commands/commands.h"
#include "app/commands/output.h"
#include "app/commands/output_path.h"
#include "app/gui/camera_framing.h"
#include "app/gui/explorer.h"
#include "app/gui/gui_app.h"
#include "app/gui/scene_loading.h"
#include "core/base/errors.h"
#include "core/base/memory_check.h"
#include "core/trace/image.h"
#include "io/png_file.h"
#include "render/field2d_view.h"
#include "render/gl/context.h"
#include "render/gl/offscreen.h"
#include "render/gl/shader_library.h"
#include "render/imgui_renderer.h"
#include "render/ui_font.h"
#include "render/implicit_tracer.h"
#include "render/legend.h"
#include "render/render_memory.h"
#include "scene/radius_sweep.h"
#include "scene/scene_fit.h"
#include "scene/view_bounds.h"

namespace hermite::app {

// "WxH" (also "W×H" with an ASCII x or X) → {W, H}, each in [1, 16384]; UsageError otherwise.
std::array<int, 2> parseImageSize(const std::string& text) {
  static const std::regex pattern(R"(^\s*([0-9]{1,5})\s*[xX]\s*([0-9]{1,5})\s*$)");
  std::smatch m;
  if (!std::regex_match(text, m, pattern))
    throw UsageError("render: --size must be WxH, e.g. 640x480 (got '" + text + "')");
  const int w = std::stoi(m[1].str()), h = std::stoi(m[2].str());
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw UsageError("render: --size must be between 1x1 and 16384x16384 (got '" + text + "')");
  return {w, h};
}

namespace {

// Fails early, before fitting and rendering: an extension other than .png is a usage error
// (render writes PNG only), a missing directory an environment error.
void checkOutputPath(const std::string& path) {
  requireExtension("render", path, {"png"});
  requireWritableLocation("render", path);
}

// A headless ImGui context sized to the image (no ini file, fixed frame time), with the
// project's GL renderer. Constructed while the GL context is current.
class HeadlessImGui {
 public:
  HeadlessImGui(int width, int height) : context_(ImGui::CreateContext()) {
    ImGuiIO& io = ImGui::GetIO();
    io.IniFilename = nullptr;
    io.LogFilename = nullptr;
    io.DisplaySize = ImVec2(float(width), float(height));
    io.DisplayFramebufferScale = ImVec2(1, 1);
    io.DeltaTime = 1.0f / 60.0f;
    ImGui::StyleColorsDark();
    render::loadUiFonts(1.0f);
    renderer_ = std::make_unique<render::ImGuiRenderer>();  // uploads the font atlas
  }
  ~HeadlessImGui() {
    renderer_.reset();
    ImGui::DestroyContext(context_);
  }
  HeadlessImGui(const HeadlessImGui&) = delete;
  HeadlessImGui& operator=(const HeadlessImGui&) = delete;

  // Runs `frames` frames of `build` (auto-sized windows settle after two) and draws the last
  // one into the framebuffer bound now.
  template <class Build>
  void draw(const Build& build, int frames = 3) {
    for (int k = 0; k < frames; ++k) {
      ImGui::NewFrame();
      build();
      ImGui::Render();
    }
    renderer_->render(ImGui::GetDrawData());
    render::checkGl("ImGui draw");
  }

 private:
  ImGuiContext* context_;
  std::unique_ptr<render::ImGuiRenderer> renderer_;
};

// Draws an ImageRgba8 texel for texel into the framebuffer bound now (same size).
void blitImage(const ImageRgba8& image) {
  render::Texture texture = render::Texture::create2D(GL_RGBA8, image.width, image.height);
  texture.setFilter(GL_NEAREST, GL_NEAREST);
  texture.upload2D(GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  render::Program program = render::buildProgram({"fullscreen.vert", "image_blit.frag"});
  render::VertexArray empty;
  program.use();
  texture.bind(0);
  program.setUniform("u_image", 0);
  program.setUniform("u_height", image.height);
  glDisable(GL_BLEND);
  glDisable(GL_DEPTH_TEST);
  empty.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindVertexArray(0);
  render::checkGl("image blit");
}

// The scene's view as `render` draws it without --ui: the same SceneViewRenderer as the window,
// settled quality (128³ bake + exact refinement in 3D, f at every pixel in 2D), at view.size;
// 2D views get their colour legend.
ImageRgba8 renderView(const Scene& scene, const RenderArgs& args) {
  const std::shared_ptr<const FitOutcome> fit = fitOutcomeOrThrow(scene);
  if (const SceneFitReport* f = fit->implicitFit()) printDataWarnings(*f);
  if (scene.view.trace == TraceMode::Exact && fit->as<SceneFit<3>>() && fit->as<SceneFit<3>>()->pu())
    // The exact shader sums one RadialSum; a partition-of-unity field is drawn from its bake.
    std::fprintf(stderr, "warning: view.trace 'exact' needs a global fit; the partition-of-unity field is traced baked\n");
  const int w = scene.view.size[0], h = scene.view.size[1];
  const auto context = offscreenContext(args.backend, w, h);
  SceneViewRenderer renderer;
  const SceneViewResult view = renderer.render(fit, scene, w, h, ViewQuality::Settled);
  if (scene.mode != SceneMode::Implicit2d) return view.image;
  // The legend on top of the field (drawn with ImGui like in the window).
  render::OffscreenTarget target(w, h, false);
  target.bind();
  blitImage(view.image);
  HeadlessImGui imgui(w, h);
  render::LegendOptions legend;
  legend.range = view.colourRange;
  legend.isoSpacing = view.isoSpacing;
  imgui.draw([&] { render::drawColorLegend(ImGui::GetBackgroundDrawList(), legend); });
  return target.read();
}

// The application itself on an offscreen context: its panels with the scene's real settings
// and diagnostics, over the view it draws (GuiApp, the same code as the window).
ImageRgba8 renderWithPanels(const Scene& scene, const RenderArgs& args) {
  const int w = scene.view.size[0], h = scene.view.size[1];
  const auto context = offscreenContext(args.backend, w, h);
  GuiOptions options;
  options.synchronousFits = true;
  options.showTimings = false;
  options.uiScale = float(args.uiScale);
  // The file name only: the same picture whatever directory the scene lives in.
  GuiApp app(Document(scene, std::filesystem::path(args.scene.scenePath).filename().string()), options);
  render::OffscreenTarget target(w, h, false);
  FrameInput in;
  in.width = w;
  in.height = h;
  if (args.explore) {
    // The panel's own default radii (a tenth to three times the scene's r), swept to the end
    // before the first frame so the strip shows every thumbnail and plot point.
    app.panels.explore = true;
    RadiusExplorer& explorer = app.explorer();
    explorer.start(scene, logSpacedRadii(explorer.lower, explorer.upper, explorer.count));
    explorer.wait();
  }
  // Auto-sized windows settle after two frames; the fit and the view are done in the first.
  for (int k = 0; k < 3; ++k) {
    target.bind();
    app.frame(in);
  }
  if (!app.shownFit()) {
    // Fit again outside the app so the failure surfaces with its own error class (exit 1 or 3).
    if (scene.mode == SceneMode::Implicit2d) fitScene<2>(scene);
    else fitScene<3>(scene);
    throw NumericalError("render: " + app.status().message);
  }
  return target.read();
}

}  // namespace

int runRender(const RenderArgs& args) {
  std::optional<std::array<int, 2>> size;
  if (!args.size.empty()) size = parseImageSize(args.size);
  if (args.output.empty()) throw UsageError("render: -o OUT.png is required");
  Scene scene = loadCommandScene(args.scene);
  if (size) scene.view.size = *size;
  checkOutputPath(args.output);
  if (args.explore && !args.ui) throw UsageError("render: --explore needs --ui (the explorer is a panel)");
  checkMemory(renderPlan(scene.view.size[0], scene.view.size[1]), kRenderRemedy);
  scene = framedOnLoad(std::move(scene));  // patch / holefill scenes without a camera: frame the content
  const ImageRgba8 image = args.ui ? renderWithPanels(scene, args) : renderView(scene, args);
  writePng(args.output, image);
  std::fprintf(stderr, "render: wrote %s (%d x %d)\n", args.output.c_str(), image.width, image.height);
  return 0;
}

}  // namespace hermite::app
