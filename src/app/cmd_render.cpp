// `hermite-lab render SCENE -o OUT.png [--size WxH] [--ui] [--set KEY=VALUE ...] [--backend osmesa|egl]`
// (DESIGN.md §5, §6): headless rendering through OSMesa (default) or EGL surfaceless. 2D scenes
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

#include "app/commands.h"
#include "app/scene_loading.h"
#include "app/ui_panels.h"
#include "core/errors.h"
#include "core/image.h"
#include "core/scene_fit.h"
#include "core/view_bounds.h"
#include "render/context.h"
#include "render/field2d_view.h"
#include "render/imgui_renderer.h"
#include "render/implicit_tracer.h"
#include "render/legend.h"
#include "render/offscreen.h"
#include "render/shader_library.h"

namespace hermite::app {

namespace {

// A hidden context of the render's size on the named backend (osmesa, egl).
std::unique_ptr<render::RenderContext> offscreenContext(const std::string& backend, int width, int height) {
  render::ContextOptions co;
  co.width = width;
  co.height = height;
  co.visible = false;
  co.vsync = false;
  return render::createContext(backend, co);
}

// "WxH" (also "W×H" with an ASCII x or X) → {W, H}, each in [1, 16384]; UsageError otherwise.
std::array<int, 2> parseSize(const std::string& text) {
  static const std::regex pattern(R"(^\s*([0-9]{1,5})\s*[xX]\s*([0-9]{1,5})\s*$)");
  std::smatch m;
  if (!std::regex_match(text, m, pattern))
    throw UsageError("render: --size must be WxH, e.g. 640x480 (got '" + text + "')");
  const int w = std::stoi(m[1].str()), h = std::stoi(m[2].str());
  if (w < 1 || h < 1 || w > 16384 || h > 16384)
    throw UsageError("render: --size must be between 1x1 and 16384x16384 (got '" + text + "')");
  return {w, h};
}

// Fails early, before fitting and rendering, when the output's directory does not exist.
void checkOutputPath(const std::string& path) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  if (p.filename().empty()) throw EnvironmentError("render: cannot write '" + path + "': not a file name");
  const fs::path dir = p.parent_path();
  std::error_code ec;
  if (!dir.empty() && !fs::is_directory(dir, ec))
    throw EnvironmentError("render: cannot write '" + path + "': directory '" + dir.string() + "' does not exist");
  if (fs::is_directory(p, ec)) throw EnvironmentError("render: cannot write '" + path + "': it is a directory");
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
    renderer_ = std::make_unique<render::ImGuiRenderer>();  // builds the font atlas
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

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

ImageRgba8 render2d(const Scene& scene, const RenderArgs& args) {
  const SceneFit<2> fit = fitScene<2>(scene);
  const HermiteSamples<2>& shown = fit.data;
  const View2d view = View2d::fromView(scene.view);

  const auto context = offscreenContext(args.backend, view.width(), view.height());

  render::Field2dViewOptions options;
  options.showPoints = scene.view.showPoints;
  options.showNormals = scene.view.showNormals;
  options.bounds = viewBounds<2>(scene.view, shown.points);
  options.outsideColor = scene.view.background;
  render::Field2dView fieldView;
  fieldView.setField(fit.field(), view, options, shown.points, shown.normals);

  render::OffscreenTarget target(view.width(), view.height(), false);
  target.bind();
  fieldView.draw();

  FitDiagnostics diagnostics;
  if (args.ui) {
    diagnostics = fitDiagnostics<2>(scene, fit);
    diagnostics.showTimings = false;  // same input → same bytes
    diagnostics.viewLines.emplace_back("colour range", fmt("\u00b1%.3g", fieldView.range()));
    diagnostics.viewLines.emplace_back("iso spacing", fmt("%.3g", fieldView.isoSpacing()));
  }
  HeadlessImGui imgui(view.width(), view.height());
  render::LegendOptions legend;
  legend.range = fieldView.range();
  legend.isoSpacing = fieldView.isoSpacing();
  imgui.draw([&] {
    render::drawColorLegend(ImGui::GetBackgroundDrawList(), legend);
    if (args.ui) drawAppPanels(diagnostics);
  });
  return target.read();
}

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

ImageRgba8 render3d(const Scene& scene, const RenderArgs& args) {
  const SceneFit<3> fit = fitScene<3>(scene);
  const HermiteSamples<3>& shown = fit.data;
  const Camera camera = Camera::fromView(scene.view);
  const Box<3> bounds = viewBounds<3>(scene.view, shown.points);

  const auto context = offscreenContext(args.backend, camera.width(), camera.height());

  render::ImplicitTracer tracer;
  tracer.upload(fit.field(), bounds, &shown);
  render::TraceSettings settings;
  settings.mode = scene.view.trace == TraceMode::Exact ? render::TracerMode::Exact : render::TracerMode::Baked;
  if (settings.mode == render::TracerMode::Exact && !tracer.hasExactModel()) {
    // The exact shader sums one RadialSum; a partition-of-unity field is drawn from its bake.
    std::fprintf(stderr, "warning: view.trace 'exact' needs a global fit; the partition-of-unity field is traced baked\n");
    settings.mode = render::TracerMode::Baked;
  }
  settings.refineExact = true;
  settings.showPoints = scene.view.showPoints;
  settings.showNormals = scene.view.showNormals;
  settings.showBounds = scene.view.showBounds;
  settings.slice.enabled = scene.view.slice.enabled;
  settings.slice.normal = scene.view.slice.normal;
  settings.slice.offset = scene.view.slice.offset;
  settings.background = scene.view.background;
  const render::TraceResult traced = tracer.render(camera, settings);
  if (!args.ui) return traced.image;

  FitDiagnostics diagnostics = fitDiagnostics<3>(scene, fit);
  diagnostics.showTimings = false;  // same input → same bytes
  diagnostics.viewLines.emplace_back("trace", settings.mode == render::TracerMode::Exact ? "exact" : "baked + refined");
  diagnostics.viewLines.emplace_back("hit pixels", std::to_string(traced.refinedPixels));
  render::OffscreenTarget target(camera.width(), camera.height(), false);
  target.bind();
  blitImage(traced.image);
  HeadlessImGui imgui(camera.width(), camera.height());
  imgui.draw([&] { drawAppPanels(diagnostics); });
  return target.read();
}

}  // namespace

int runRender(const RenderArgs& args) {
  std::optional<std::array<int, 2>> size;
  if (!args.size.empty()) size = parseSize(args.size);
  if (args.output.empty()) throw UsageError("render: -o OUT.png is required");
  Scene scene = loadCommandScene(args.scene);
  if (size) scene.view.size = *size;
  if (scene.mode != SceneMode::Implicit2d && scene.mode != SceneMode::Implicit3d)
    throw InputError("render: mode '" + std::string(sceneModeName(scene.mode)) +
                     "' is not available in this version");
  checkOutputPath(args.output);
  const ImageRgba8 image = scene.mode == SceneMode::Implicit2d ? render2d(scene, args) : render3d(scene, args);
  writePng(args.output, image);
  return 0;
}

}  // namespace hermite::app
