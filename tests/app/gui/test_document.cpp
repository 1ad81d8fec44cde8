// The document's unsaved-changes flag and the window title built from it.

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "app/gui/document.h"
#include "support/temp_dir.h"

using namespace hermite;
using namespace hermite::app;

namespace {

Scene pointsScene() {
  Scene s;
  s.mode = SceneMode::Implicit2d;
  s.data.preset = "circle";
  return s;
}

}  // namespace

TEST_CASE("document: modified after an edit, clean again when undo returns to the opened scene") {
  Document d(pointsScene(), "lecture/circle.json");
  CHECK_FALSE(d.dirty());
  CHECK(documentTitle(d) == "Hermite Lab — circle.json");
  Scene s = d.scene();
  s.fit.radius = 0.25;
  d.apply(s, "radius");
  CHECK(d.dirty());
  CHECK(documentTitle(d) == "Hermite Lab — circle.json *");
  d.undo();
  CHECK_FALSE(d.dirty());
  d.redo();
  CHECK(d.dirty());
  // A camera move away and back: modified, then clean.
  const CameraSpec c0 = d.scene().view.camera;
  d.undo();
  CameraSpec moved = c0;
  moved.eye[0] += 1;
  d.setCamera(moved, d.scene().view.center2d, d.scene().view.halfHeight2d);
  CHECK(d.dirty());
  d.setCamera(c0, d.scene().view.center2d, d.scene().view.halfHeight2d);
  CHECK_FALSE(d.dirty());
}

TEST_CASE("document: saving makes the saved scene the clean one; the title names the data file without a scene") {
  Document demo(pointsScene());
  CHECK(documentTitle(demo) == "Hermite Lab — demo scene");
  Scene fromFile = pointsScene();
  fromFile.data.preset.clear();
  fromFile.data.file = "/data/scans/kitten.xyz";
  CHECK(documentTitle(Document(fromFile)) == "Hermite Lab — kitten.xyz");

  const std::string path = (std::filesystem::temp_directory_path() / "hermite_document_title.json").string();
  Scene s = demo.scene();
  s.fit.radius = 0.4;
  demo.apply(s, "radius");
  demo.save(path);
  CHECK_FALSE(demo.dirty());
  CHECK(documentTitle(demo) == "Hermite Lab — hermite_document_title.json");
  demo.undo();  // back to the scene before the save: now that one is a change
  CHECK(demo.dirty());
  demo.redo();
  CHECK_FALSE(demo.dirty());
  std::filesystem::remove(path);
}

TEST_CASE("document: a data file's samples made inline for editing keep its data reach; a preset's stay whole") {
  const testing::TempDir dir;
  std::string text;
  for (int i = 0; i < 60; ++i) {  // an open arc: a scan, not a hand-made file (at least 50 samples)
    const double t = 0.5 + 2.0 * i / 59.0;
    text += std::to_string(std::cos(t)) + " " + std::to_string(std::sin(t)) + " " + std::to_string(std::cos(t)) + " " +
            std::to_string(std::sin(t)) + "\n";
  }
  Scene file;
  file.mode = SceneMode::Implicit2d;
  file.data.file = file.data.resolvedFile = dir.write("arc.xyn", text);
  std::vector<std::string> warnings;
  const Scene edited = withInlineSamples<2>(file, warnings);
  CHECK(edited.data.isInline());
  CHECK(edited.fit.reachMask == AutoSwitch::On);
  const Scene preset = withInlineSamples<2>(pointsScene(), warnings);
  CHECK(preset.fit.reachMask == AutoSwitch::Auto);
  file.fit.reachMask = AutoSwitch::Off;  // asked for: stays
  CHECK(withInlineSamples<2>(file, warnings).fit.reachMask == AutoSwitch::Off);
}
