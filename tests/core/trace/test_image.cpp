#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

#include "core/base/errors.h"
#include "core/trace/image.h"
#include "io/png_file.h"

using namespace hermite;

namespace {

std::string tempDir() {
  const std::filesystem::path d = std::filesystem::temp_directory_path() / ("hermite_image_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(d);
  return d.string();
}

}  // namespace

TEST_CASE("image: PNG round trip is exact") {
  ImageRgba8 img(7, 5);
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 7; ++i) {
      std::uint8_t* p = img.at(i, j);
      p[0] = std::uint8_t(i * 30);
      p[1] = std::uint8_t(j * 50);
      p[2] = std::uint8_t((i * j * 7) % 256);
      p[3] = std::uint8_t(255 - i);
    }
  const std::string dir = tempDir();
  const std::string path = dir + "/round.png";
  writePng(path, img);
  const ImageRgba8 back = readPng(path);
  CHECK(back == img);
  CHECK(encodePng(img).substr(1, 3) == "PNG");
  std::filesystem::remove_all(dir);
}

TEST_CASE("image: unreadable or unwritable PNG paths are EnvironmentErrors naming the path") {
  const ImageRgba8 img(2, 2);
  try {
    writePng("/nonexistent-dir-hermite/x.png", img);
    FAIL("no throw");
  } catch (const EnvironmentError& e) {
    CHECK(std::string(e.what()).find("/nonexistent-dir-hermite") != std::string::npos);
  }
  CHECK_THROWS_AS(readPng("/nonexistent-dir-hermite/x.png"), EnvironmentError);
  const std::string dir = tempDir();
  {
    std::ofstream(dir + "/bad.png") << "not a png";
  }
  CHECK_THROWS_AS(readPng(dir + "/bad.png"), EnvironmentError);
  std::filesystem::remove_all(dir);
}

TEST_CASE("image: IoU and diff statistics") {
  CHECK(maskIoU({0, 0}, {0, 0}) == 1.0);
  CHECK(maskIoU({1, 1, 0, 0}, {1, 0, 1, 0}) == doctest::Approx(1.0 / 3.0));
  CHECK(maskIoU({1, 1, 0}, {1, 1, 0}) == 1.0);
  CHECK_THROWS_AS(maskIoU({1}, {1, 0}), InputError);

  ImageRgba8 a(4, 4), b(4, 4);
  a.fill(100, 100, 100);
  b.fill(100, 100, 100);
  b.at(1, 1)[0] = 103;
  b.at(2, 3)[2] = 101;
  const ImageDiffStats s = compareImages(a, b, 2);
  CHECK(s.maxChannelDiff == 3);
  CHECK(s.pixelsOver == 1);
  CHECK(s.fractionOver == doctest::Approx(1.0 / 16));
  const ImageRgba8 d = diffImage(a, b, 2);
  CHECK(d.at(1, 1)[0] > d.at(1, 1)[1]);
  CHECK(d.at(2, 3)[0] == d.at(2, 3)[1]);
}
