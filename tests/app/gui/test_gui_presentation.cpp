// Type, scale, presenter mode, messages and legends (issue 19 items 1, 5, 7): the UI font draws
// every glyph the program writes, at every scale and in every mode; the status bar and the
// message log keep messages whole; each colour with a meaning has a legend.

#include <doctest/doctest.h>

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "app/gui/camera_framing.h"
#include "app/gui/view_colours.h"
#include "core/trace/shading.h"
#include "io/png_file.h"
#include "scene/scene_fit.h"
#include "support/gui_harness.h"

using namespace hermite;
using namespace hermite::app;
using hermite::app::testing::Harness;

namespace {

Scene curveScene() {
  Scene s;
  s.mode = SceneMode::Implicit2d;
  s.data.preset = "curve2d";
  s.data.count = 24;
  s.fit.kernel = KernelType::Gaussian;
  s.fit.radius = 0.3;
  s.fit.polynomial = Polynomial::Linear;
  s.sourceName = "test-2d";
  return s;
}

Scene sphereScene(bool slice) {
  Scene s;
  s.mode = SceneMode::Implicit3d;
  s.data.preset = "sphere";
  s.data.count = 40;
  s.view.slice.enabled = slice;
  s.sourceName = "test-3d";
  return s;
}

Scene patchScene() {
  Scene s;
  s.mode = SceneMode::Patch;
  s.patch.preset = "torus";
  s.patch.splits = {2, 2};
  s.sourceName = "test-patch";
  return framedOnLoad(s);
}

Scene holeFillScene() {
  Scene s;
  s.mode = SceneMode::HoleFill;
  s.holefill.preset = "sphere";
  s.sourceName = "test-holefill";
  return framedOnLoad(s);
}

GuiOptions scaled(float scale) {
  GuiOptions o;
  o.uiScale = scale;
  o.showTimings = false;
  return o;
}

void openEveryPanel(GuiApp& app) {
  app.panels.data = app.panels.fit = app.panels.compare = app.panels.transform = true;
  app.panels.view = app.panels.diagnostics = app.panels.help = app.panels.messages = true;
}

// Pixels of exactly colour c (linear [0, 1], 8-bit rounded) in the image's rectangle [x0, x1) × [y0, y1).
int countColour(const ImageRgba8& image, const std::array<double, 3>& c, int x0, int y0, int x1, int y1) {
  int n = 0;
  for (int j = std::max(0, y0); j < std::min(image.height, y1); ++j)
    for (int i = std::max(0, x0); i < std::min(image.width, x1); ++i) {
      const std::uint8_t* p = image.at(i, j);
      n += p[0] == std::lround(255 * c[0]) && p[1] == std::lround(255 * c[1]) && p[2] == std::lround(255 * c[2]);
    }
  return n;
}

}  // namespace

TEST_CASE("UI font: the glyph-miss counter counts a code point the font lacks, and none of ours") {
  Harness h(curveScene());
  h.frames(2);
  REQUIRE(h.app->shownFit());
  CHECK(h.app->glyphMisses() == 0);
  // An error naming a file shows the name in the status bar: the maths every message uses ...
  h.input.droppedFiles = {"/nonexistent/\xE2\x89\xA5\xE2\x80\x94\xC3\x97\xE1\xB5\x80\xCF\x86\xE2\x80\xB2\xCE\xBB\xE2\x89\xA0\xC2\xB2.xyz"};
  h.frames(2);
  CHECK(h.app->status().error);
  CHECK(h.app->glyphMisses() == 0);
  // ... and two CJK characters the UI font does not carry: one fallback glyph each, per frame.
  h.input.droppedFiles = {"/nonexistent/\xE4\xB8\xAD\xE6\x96\x87.xyz"};
  h.frame();
  CHECK(h.app->glyphMisses() == 2);
}

TEST_CASE("UI font: each mode at scale 2 shows every glyph (screenshots with every panel open)") {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "hermite_ui_scale2";
  std::filesystem::create_directories(dir);
  struct Case {
    const char* name;
    Scene scene;
    bool presenter = false;
  };
  const Case cases[] = {{"implicit2d", curveScene()},         {"implicit3d", sphereScene(true)},
                        {"patch", patchScene()},              {"holefill", holeFillScene()},
                        {"presenter3d", sphereScene(false), true}};
  for (const Case& c : cases) {
    CAPTURE(c.name);
    Harness h(c.scene, true, 1600, 1000, scaled(2.0f));
    openEveryPanel(*h.app);
    h.app->panels.presenter = c.presenter;
    if (c.scene.mode == SceneMode::Implicit2d) {
      h.app->compare.enabled = true;
      h.app->panels.explore = true;
      h.frames(2);
      h.app->explorer().start(h.app->document().scene(), logSpacedRadii(0.1, 1.0, 3));
      h.app->explorer().wait();
    }
    h.frames(3);
    REQUIRE(h.app->shownFit());
    CHECK(h.app->fontPixels() == doctest::Approx(26.0f));
    const std::string path = (dir / (std::string(c.name) + ".png")).string();
    h.app->requestScreenshot(path, true);
    h.frame();
    CHECK(h.app->glyphMisses() == 0);
    const ImageRgba8 shot = readPng(path);
    CHECK(shot.width == 1600);
    CHECK(shot.height == 1000);
  }
}

TEST_CASE("UI scale: Ctrl + / Ctrl - / Ctrl 0 re-rasterise the type at the new size and move the view") {
  Harness h(curveScene());
  h.frames(2);
  CHECK(h.app->fontPixels() == doctest::Approx(13.0f));
  const double viewX = h.app->viewOrigin().x();
  CHECK(viewX == doctest::Approx(kLeftPanelWidth));
  h.key(GLFW_KEY_EQUAL, true);
  CHECK(h.app->uiScale() == doctest::Approx(1.25f));
  CHECK(h.app->fontPixels() == doctest::Approx(16.0f));  // round(13 · 1.25)
  CHECK(h.app->viewOrigin().x() == doctest::Approx(std::floor(1.25 * kLeftPanelWidth)));
  h.key(GLFW_KEY_MINUS, true);
  h.key(GLFW_KEY_KP_SUBTRACT, true);
  CHECK(h.app->uiScale() == doctest::Approx(0.75f));
  CHECK(h.app->fontPixels() == doctest::Approx(10.0f));
  h.key(GLFW_KEY_0, true);
  CHECK(h.app->uiScale() == doctest::Approx(1.0f));
  CHECK(h.app->fontPixels() == doctest::Approx(13.0f));
  CHECK(h.app->glyphMisses() == 0);
}

TEST_CASE("Presenter mode: F5 hides the panels; the caption names method, kernel, r, polynomial and N") {
  Harness h(curveScene());
  h.frames(2);
  REQUIRE(h.app->shownFit());
  CHECK(h.app->viewSize().x() == doctest::Approx(1000 - kLeftPanelWidth));
  h.key(GLFW_KEY_F5);
  CHECK(h.app->viewSize().x() == doctest::Approx(1000));
  CHECK(h.app->viewSize().y() == doctest::Approx(700));
  const std::string caption = h.app->presenterCaption();
  CAPTURE(caption);
  for (const char* part : {"hrbf", "gaussian", "r = 0.3", "spacing)", "linear polynomial", "N = 24"})
    CHECK(caption.find(part) != std::string::npos);
  CHECK(h.app->glyphMisses() == 0);
  h.key(GLFW_KEY_F5);
  CHECK(h.app->viewSize().x() == doctest::Approx(1000 - kLeftPanelWidth));
  // view.presenter starts a scene in presenter mode.
  Scene s = curveScene();
  s.view.presenter = true;
  Harness p(s);
  p.frames(1);
  CHECK(p.app->viewSize().x() == doctest::Approx(1000));
}

TEST_CASE("Status bar: path and message apart, two lines at most; the log keeps every message whole") {
  Harness h(curveScene());
  h.frames(2);
  std::string longName = "/nonexistent/";
  for (int k = 0; k < 30; ++k) longName += "a-rather-long-folder-name/";
  longName += "points.xyz";
  h.input.droppedFiles = {longName};
  h.frames(2);
  REQUIRE(h.app->status().error);
  const LogEntry& last = h.app->status().log.back();
  CHECK(last.severity == Severity::Error);
  CHECK(last.text == h.app->status().message);
  CHECK(last.text.find(longName) != std::string::npos);
  const auto path = h.app->widgetRect("status.path"), message = h.app->widgetRect("status.message");
  REQUIRE(path);
  REQUIRE(message);
  CHECK((*path)[2] <= (*message)[0]);                      // side by side, never drawn over each other
  CHECK((*message)[3] - (*message)[1] <= 2 * 13.0f + 2.0f);  // cut to two lines of 13 px type
  CHECK((*message)[3] <= 700.0f);
  // F2 opens the message log window, F2 again closes it.
  CHECK_FALSE(h.app->widgetRect("messages.clear"));
  h.key(GLFW_KEY_F2);
  CHECK(h.app->widgetRect("messages.clear"));
  h.key(GLFW_KEY_F2);
  h.frame();
  CHECK_FALSE(h.app->widgetRect("messages.clear"));
}

TEST_CASE("r slider: Shift+drag takes fine steps of 0.2 % per pixel") {
  Harness h(curveScene());
  h.frames(2);
  const auto rect = h.app->widgetRect("fit.radius");
  REQUIRE(rect);
  const double r0 = h.app->document().scene().fit.radius;
  const double x = 0.5 * ((*rect)[0] + (*rect)[2]), y = 0.5 * ((*rect)[1] + (*rect)[3]);
  h.input.shift = true;
  h.drag(x, y, x + 50, y, 5);
  h.input.shift = false;
  const double r1 = h.app->document().scene().fit.radius;
  CHECK(r1 / r0 == doctest::Approx(std::pow(1.002, 50)).epsilon(1e-9));
}

TEST_CASE("Legends: 3D surface colours (outside / inside) and the slice bar; hole-fill colours") {
  {
    Harness h(sphereScene(true), true, 900, 650);
    h.frames(3);
    REQUIRE(h.app->shownFit());
    CHECK(h.app->viewResult().colourRange > 0);  // the slice's range, for its colour bar
    const ImageRgba8 frame = h.target->read();
    const int right = 900, bottom = 650 - int(kStatusBarHeight);
    CHECK(countColour(frame, shading::kFrontColor, right - 260, bottom - 250, right, bottom) > 50);
    CHECK(countColour(frame, shading::kBackColor, right - 260, bottom - 250, right, bottom) > 50);
  }
  {
    Harness h(holeFillScene(), true, 900, 650);
    h.frames(3);
    REQUIRE(h.app->shownFit());
    const ImageRgba8 frame = h.target->read();
    const int right = 900, bottom = 650 - int(kStatusBarHeight);
    CHECK(countColour(frame, kHolePatchColour, right - 260, bottom - 100, right, bottom) > 50);
    CHECK(countColour(frame, kHoleRimColour, right - 260, bottom - 100, right, bottom) > 50);
  }
}
