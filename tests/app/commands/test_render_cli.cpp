// `hermite-lab render` through the real executable: PNG output, determinism, --ui, the EGL
// backend, golden images and exit codes (docs/cli.md; docs/design.md, Testing).
//
// Golden PNGs live in tests/golden/render_*.png. They are compared by tolerance (≤ 2/255 per
// channel on ≤ 0.1 % of the pixels; exact bytes vary with the CPU's code generation); on a
// mismatch a diff image is written next to the render and its path printed. To regenerate them
// after an intended change, look at the new renders, then run
//   HERMITE_UPDATE_GOLDEN=1 build/release/hermite_app_tests -tc='render golden*'

#include <doctest/doctest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "core/trace/image.h"
#include "io/png_file.h"
#include "support/cli_runner.h"

using namespace hermite;
using hermite::testing::runCli;

namespace {

namespace fs = std::filesystem;

constexpr int kTolerance = 2;            // per channel, of 255
constexpr double kMaxFractionOver = 1e-3;  // of the pixels

std::string scene(const std::string& name) { return std::string(HERMITE_SOURCE_DIR) + "/assets/scenes/" + name; }

// Well-conditioned fits: the same field on every CPU, so goldens hold across machines.
const std::string kScene2d = scene("gaussian2d_40pts_r0.2_none.json");
const std::string kScene3d = scene("polyharmonic_bunny_64pts_quadratic.json");

std::string outputPath(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("hermite_render_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return (dir / name).string();
}

// Renders `args` to OUT (a temp file named `name`) and requires exit 0 and a readable PNG.
ImageRgba8 render(const std::string& args, const std::string& name) {
  const std::string out = outputPath(name);
  fs::remove(out);
  const auto r = runCli("render " + args + " -o " + out);
  INFO("stderr: " << r.err);
  REQUIRE(r.rc == 0);
  CHECK(r.out.empty());  // stdout stays clean
  REQUIRE(fs::exists(out));
  return readPng(out);
}

bool updateGoldens() {
  const char* v = std::getenv("HERMITE_UPDATE_GOLDEN");
  return v != nullptr && std::strcmp(v, "1") == 0;
}

bool skipEgl() {
  const char* v = std::getenv("HERMITE_SKIP_EGL");
  return v != nullptr && std::strcmp(v, "1") == 0;
}

// Compares a render with tests/golden/NAME.png by tolerance; writes OUT.diff.png on failure.
void checkGolden(const std::string& args, const std::string& name) {
  const ImageRgba8 image = render(args, name + ".png");
  const fs::path golden = fs::path(HERMITE_SOURCE_DIR) / "tests" / "golden" / (name + ".png");
  if (updateGoldens()) {
    writePng(golden.string(), image);
    MESSAGE("updated " << golden.string());
    return;
  }
  REQUIRE_MESSAGE(fs::exists(golden), "missing golden " << golden.string() << " (HERMITE_UPDATE_GOLDEN=1 makes it)");
  const ImageRgba8 expected = readPng(golden.string());
  REQUIRE(expected.width == image.width);
  REQUIRE(expected.height == image.height);
  const ImageDiffStats stats = compareImages(image, expected, kTolerance);
  if (stats.fractionOver > kMaxFractionOver) {
    const std::string diff = outputPath(name + ".diff.png");
    writeDiffImage(diff, image, expected, kTolerance);
    MESSAGE("golden mismatch for " << name << ": " << stats.pixelsOver << " pixels over " << kTolerance
                                   << "/255 (max " << stats.maxChannelDiff << "); diff image " << diff);
  }
  CHECK(stats.fractionOver <= kMaxFractionOver);
}

}  // namespace

TEST_CASE("render: a 2D scene gives a PNG of the requested size, the same bytes twice") {
  const std::string a = outputPath("twice_a.png"), b = outputPath("twice_b.png");
  const auto r1 = runCli("render " + kScene2d + " --size 160x120 -o " + a);
  const auto r2 = runCli("render " + kScene2d + " --size 160x120 -o " + b);
  INFO(r1.err << r2.err);
  REQUIRE(r1.rc == 0);
  REQUIRE(r2.rc == 0);
  CHECK(r1.out.empty());
  const ImageRgba8 image = readPng(a);
  CHECK(image.width == 160);
  CHECK(image.height == 120);
  CHECK(testing::readAll(a) == testing::readAll(b));
}

TEST_CASE("render: a 3D scene gives a PNG of the requested size, the same bytes twice") {
  const std::string a = outputPath("twice3_a.png"), b = outputPath("twice3_b.png");
  const auto r1 = runCli("render " + kScene3d + " --size 160x120 -o " + a);
  const auto r2 = runCli("render " + kScene3d + " --size 160x120 -o " + b);
  INFO(r1.err << r2.err);
  REQUIRE(r1.rc == 0);
  REQUIRE(r2.rc == 0);
  const ImageRgba8 image = readPng(a);
  CHECK(image.width == 160);
  CHECK(image.height == 120);
  CHECK(testing::readAll(a) == testing::readAll(b));
  // The surface is there: not every pixel is the white background.
  int covered = 0;
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      const std::uint8_t* p = image.at(i, j);
      covered += (p[0] != 255 || p[1] != 255 || p[2] != 255) ? 1 : 0;
    }
  CHECK(covered > 1000);
}

TEST_CASE("render --ui draws the application: panels on the left, the same view beside them") {
  // 800 × 500 window: the left panel is 330 px wide, the status bar 40 px high (two lines), so
  // the view is 470 × 460 — exactly what `render --size 470x460` draws.
  const ImageRgba8 ui = render(kScene2d + " --size 800x500 --ui", "ui.png");
  const ImageRgba8 plain = render(kScene2d + " --size 470x460", "plain.png");
  // No wall-clock figures in headless panels: the same bytes twice.
  const ImageRgba8 again = render(kScene2d + " --size 800x500 --ui", "ui_again.png");
  CHECK(again == ui);
  REQUIRE(ui.width == 800);
  REQUIRE(ui.height == 500);
  // The left panel: dark window background with light text.
  int dark = 0, light = 0;
  for (int j = 40; j < 200; ++j)
    for (int i = 8; i < 300; ++i) {
      const std::uint8_t* p = ui.at(i, j);
      dark += (p[0] < 70 && p[1] < 70 && p[2] < 90) ? 1 : 0;
      light += (p[0] > 180 && p[1] > 180 && p[2] > 180) ? 1 : 0;
    }
  CHECK(dark > 160 * 292 / 3);
  CHECK(light > 300);
  // The view's lower-left region (clear of the diagnostics panel and the legend) is the plain
  // render, pixel for pixel.
  int same = 0, total = 0;
  for (int j = 300; j < 460; ++j)
    for (int i = 0; i < 200; ++i) {
      ++total;
      same += std::memcmp(ui.at(330 + i, j), plain.at(i, j), 4) == 0 ? 1 : 0;
    }
  CHECK(same >= total * 99 / 100);
}

TEST_CASE("render --ui --ui-scale 2: the panel column twice as wide, the view beside it") {
  const ImageRgba8 ui = render(kScene2d + " --size 1600x800 --ui --ui-scale 2", "ui_scale2.png");
  REQUIRE(ui.width == 1600);
  const auto panelDark = [&](int i, int j) {
    const std::uint8_t* p = ui.at(i, j);
    return p[0] < 70 && p[1] < 70 && p[2] < 90;
  };
  // The panel column is 660 px wide (330 at scale 1): mostly its dark background between x = 340
  // and 650, the view (light heat map) between 680 and 990.
  const auto darkFraction = [&](int x0, int x1) {
    int dark = 0;
    for (int j = 200; j < 600; ++j)
      for (int i = x0; i < x1; ++i) dark += panelDark(i, j) ? 1 : 0;
    return double(dark) / (400.0 * (x1 - x0));
  };
  CHECK(darkFraction(340, 650) > 0.3);
  CHECK(darkFraction(680, 990) < 0.05);
}

TEST_CASE("render --ui --explore: the r explorer strip under the view, its sweep finished") {
  const ImageRgba8 plain = render(kScene2d + " --size 1280x800 --ui", "ui_plain.png");
  const ImageRgba8 ui = render(kScene2d + " --size 1280x800 --ui --explore", "ui_explore.png");
  // The strip (200 px over the 20 px status bar, right of the 330 px panel column) is the dark
  // panel background with plots and thumbnails; without --explore the light view is there.
  const auto darkFraction = [](const ImageRgba8& image) {
    int dark = 0, total = 0;
    for (int j = 590; j < 770; j += 2)
      for (int i = 340; i < 1270; i += 2, ++total) {
        const std::uint8_t* p = image.at(i, j);
        dark += p[0] < 70 && p[1] < 70 && p[2] < 90 ? 1 : 0;
      }
    return double(dark) / total;
  };
  CHECK(darkFraction(ui) > 0.5);
  CHECK(darkFraction(plain) < 0.2);
}

TEST_CASE("render --backend egl agrees with osmesa") {
  if (skipEgl()) return;
  for (const std::string& s : {kScene2d, kScene3d}) {
    CAPTURE(s);
    const ImageRgba8 osmesa = render(s + " --size 160x120", "backend_osmesa.png");
    const ImageRgba8 egl = render(s + " --size 160x120 --backend egl", "backend_egl.png");
    REQUIRE(egl.width == osmesa.width);
    const ImageDiffStats stats = compareImages(egl, osmesa, kTolerance);
    CHECK(stats.fractionOver <= kMaxFractionOver);
  }
}

TEST_CASE("render golden images (2D, 3D, slice plane, with and without --ui)") {
  checkGolden(kScene2d + " --size 200x150", "render_2d");
  checkGolden(kScene2d + " --size 800x500 --ui", "render_2d_ui");
  checkGolden(kScene3d + " --size 160x120", "render_3d");
  checkGolden(kScene3d + " --size 160x120 --set view.slice.enabled=true --set view.slice.normal=[0,0,1]"
                         " --set view.camera.eye=[2,2.5,3]",
              "render_3d_slice");
  checkGolden(kScene3d + " --size 800x500 --ui", "render_3d_ui");
}

// Pixels that differ from the white background by more than 8/255 in some channel.
double contentFraction(const ImageRgba8& image) {
  std::size_t content = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const std::uint8_t* p = image.at(x, y);
      content += p[0] < 247 || p[1] < 247 || p[2] < 247;
    }
  return double(content) / (double(image.width) * image.height);
}

TEST_CASE("render frames the patch and the mesh to fill when the scene names no camera") {
  const std::string minimal = std::string(HERMITE_SOURCE_DIR) + "/tests/fixtures/scenes/minimal.json";
  const std::string patch = minimal + " --set mode=patch --set patch.preset=torus --size 160x120";
  const std::string holefill = minimal + " --set mode=holefill --size 160x120";
  // The default camera looks at the origin from z = 4: the torus piece lies off to the side.
  CHECK(contentFraction(render(patch, "patch.png")) > 0.05);
  CHECK(contentFraction(render(holefill, "holefill.png")) > 0.05);
  // A camera of the scene's own is kept: looking away from the patch shows nothing of it.
  CHECK(contentFraction(render(patch + " --set view.camera.eye=[0,0,-40] --set view.camera.target=[0,0,-50]",
                               "patch_away.png")) < 0.001);
  checkGolden(patch, "render_patch");
  checkGolden(holefill, "render_holefill");
}

TEST_CASE("render: exit codes") {
  SUBCASE("unwritable output path → 4") {
    const auto r = runCli("render " + kScene2d + " --size 32x32 -o /nonexistent/dir/x.png");
    CHECK(r.rc == 4);
    CHECK(r.err.find("/nonexistent/dir") != std::string::npos);
  }
  SUBCASE("no GL context → 4") {
    // EGL cannot find its driver: context creation fails cleanly.
    ::setenv("LIBGL_DRIVERS_PATH", "/nonexistent", 1);
    const auto r = runCli("render " + kScene2d + " --size 32x32 --backend egl -o " + outputPath("x.png"));
    ::unsetenv("LIBGL_DRIVERS_PATH");
    CHECK(r.rc == 4);
    CHECK(r.err.find("environment error: egl") != std::string::npos);
  }
  SUBCASE("missing -o → 2") {
    const auto r = runCli("render " + kScene2d);
    CHECK(r.rc == 2);
    CHECK(r.err.find("-o") != std::string::npos);
  }
  SUBCASE("malformed --size → 2") {
    CHECK(runCli("render " + kScene2d + " --size 12by4 -o " + outputPath("x.png")).rc == 2);
    CHECK(runCli("render " + kScene2d + " --size 0x10 -o " + outputPath("x.png")).rc == 2);
  }
  SUBCASE("--ui-scale outside 0.5 to 4 → 2") {
    const auto r = runCli("render " + kScene2d + " --ui --ui-scale 9 -o " + outputPath("x.png"));
    CHECK(r.rc == 2);
    CHECK(r.err.find("--ui-scale") != std::string::npos);
  }
  SUBCASE("--explore without --ui → 2") {
    const auto r = runCli("render " + kScene2d + " --explore -o " + outputPath("x.png"));
    CHECK(r.rc == 2);
    CHECK(r.err.find("--explore needs --ui") != std::string::npos);
  }
  SUBCASE("unknown backend → 2") {
    CHECK(runCli("render " + kScene2d + " --backend vulkan -o " + outputPath("x.png")).rc == 2);
  }
  SUBCASE("unknown key via --set → 1") {
    const auto r = runCli("render " + kScene2d + " --set view.colour=1 -o " + outputPath("x.png"));
    CHECK(r.rc == 1);
    CHECK(r.err.find("view.colour") != std::string::npos);
  }
  SUBCASE("a holefill scene whose mesh file is missing → 1, naming the file") {
    const auto r = runCli("render " + kScene2d + " --set mode=holefill --set holefill.mesh=no-such-mesh.obj -o " +
                          outputPath("x.png"));
    CHECK(r.rc == 1);
    CHECK(r.err.find("no-such-mesh.obj") != std::string::npos);
  }
  SUBCASE("patch and holefill scenes render") {
    CHECK(runCli("render " + kScene2d + " --set mode=patch --size 64x48 -o " + outputPath("p.png")).rc == 0);
    CHECK(runCli("render " + kScene2d + " --set mode=holefill --set holefill.stage=fair --size 64x48 -o " +
                 outputPath("h.png")).rc == 0);
  }
}
