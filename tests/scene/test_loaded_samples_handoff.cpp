#include <doctest/doctest.h>

#include <chrono>
#include <filesystem>

#include "scene/loaded_samples_handoff.h"
#include "support/temp_dir.h"

using namespace hermite;

namespace {

HermiteSamples<3> twoSamples(double x) {
  HermiteSamples<3> s;
  s.points = Points<3>::Zero(3, 2);
  s.normals = Points<3>::Zero(3, 2);
  s.points(0, 1) = x;
  s.normals.row(2).setOnes();
  return s;
}

}  // namespace

// A data file opened as a scene is parsed once: its default scene's read hands the samples to the
// fit's, and only while nothing about the file or the options changed.
TEST_CASE("loaded samples hand-off: taken once, and only for the same unchanged file and options") {
  testing::TempDir dir("hermite_handoff");
  const std::string path = dir.write("a.xyzn", "0 0 0 0 0 1\n1 0 0 0 0 1\n");
  const PointFileOptions options;
  std::vector<std::string> warnings;

  keepLoadedSamples<3>(path, options, twoSamples(0.5), {"w1"});
  auto kept = takeLoadedSamples<3>(path, options, warnings);
  REQUIRE(kept);
  CHECK(kept->points(0, 1) == 0.5);
  CHECK(warnings == std::vector<std::string>{"w1"});
  CHECK_FALSE(takeLoadedSamples<3>(path, options, warnings));  // taken once
  CHECK_FALSE(takeLoadedSamples<2>(path, options, warnings));  // another dimension has nothing

  keepLoadedSamples<3>(path, options, twoSamples(0.5), {});
  CHECK_FALSE(takeLoadedSamples<3>(path, PointFileOptions{GivenNormals::Never}, warnings));
  CHECK_FALSE(takeLoadedSamples<3>(path, options, warnings));  // a mismatch drops the entry

  keepLoadedSamples<3>(path, options, twoSamples(0.5), {});
  CHECK_FALSE(takeLoadedSamples<3>(dir.write("b.xyzn", "0 0 0 0 0 1\n"), options, warnings));

  // The file changed after it was read (same size, a later modification time): read again.
  keepLoadedSamples<3>(path, options, twoSamples(0.5), {});
  std::filesystem::last_write_time(path, std::filesystem::last_write_time(path) + std::chrono::seconds(2));
  CHECK_FALSE(takeLoadedSamples<3>(path, options, warnings));
  CHECK(warnings.size() == 1);
}
