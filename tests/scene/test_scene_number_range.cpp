// Numbers at the edges of the double range in scene files: input errors naming the key.

#include <doctest/doctest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "core/base/errors.h"
#include "scene/scene_file.h"

namespace fs = std::filesystem;

namespace {

std::string loadError(const std::string& name, const std::string& text) {
  const fs::path path = fs::temp_directory_path() / ("hermite_range_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path) << text;
  std::string message = "(no error)";
  try {
    hermite::loadSceneFile(path.string());
  } catch (const hermite::InputError& e) {
    message = e.what();
  }
  fs::remove(path);
  return message;
}

}  // namespace

TEST_CASE("a number beyond the double range is an input error naming the file and the key") {
  const std::string m = loadError("overflow.json", R"({"version": 1, "mode": "implicit2d",
    "data": {"preset": "circle", "count": 8}, "fit": {"kernel": "gaussian", "radius": 1e400}})");
  CAPTURE(m);
  CHECK(m.find("overflow.json") != std::string::npos);
  CHECK(m.find("fit.radius") != std::string::npos);
  CHECK(m.find("1e400") != std::string::npos);
}

TEST_CASE("smoothing beyond 1e100 is refused with the key; 1e100 itself is accepted") {
  const std::string scene = R"({"version": 1, "mode": "implicit2d", "data": {"preset": "circle", "count": 8},
    "fit": {"smoothing": SMOOTHING}})";
  auto with = [&](const std::string& v) {
    std::string s = scene;
    s.replace(s.find("SMOOTHING"), 9, v);
    return s;
  };
  const std::string m = loadError("smooth.json", with("1e308"));
  CAPTURE(m);
  CHECK(m.find("fit.smoothing") != std::string::npos);
  CHECK(m.find("1e100") != std::string::npos);
  CHECK(loadError("smooth_ok.json", with("1e100")) == "(no error)");
}
