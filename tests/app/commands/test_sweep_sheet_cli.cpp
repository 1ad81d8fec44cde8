// `sweep` images carry a caption; `--sheet` writes a contact sheet of them (issue 19 item 4).

#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "app/commands/image_caption.h"
#include "io/png_file.h"
#include "support/cli_runner.h"
#include "support/temp_dir.h"

using namespace hermite;
using namespace hermite::testing;

namespace {

// Pixels of `im` within rows [y0, y1) that are (near) white / (near) the 30 % darkened white.
int countPixels(const ImageRgba8& im, int y0, int y1, int lo, int hi) {
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < im.width; ++x)
      if (im.at(x, y)[0] >= lo && im.at(x, y)[0] <= hi) ++n;
  return n;
}

}  // namespace

TEST_CASE("caption: a dark band across the bottom with white glyphs in it; the picture above is untouched") {
  ImageRgba8 im(200, 60);
  im.fill(255, 255, 255);
  app::burnCaption(im, {"wendland r = 0.25"}, 1);
  const int band = app::captionLineHeight(1);
  CHECK(band == 19);
  CHECK(countPixels(im, 0, im.height - band, 255, 255) == 200 * (60 - band));  // above: white
  const int dark = countPixels(im, im.height - band, im.height, 70, 80);       // 255·0.3 = 76
  const int glyph = countPixels(im, im.height - band, im.height, 200, 255);
  CHECK(dark > 200 * band / 2);
  CHECK(glyph > 40);  // 17 glyphs of a few pixels each
  // Too short for the band: unchanged.
  ImageRgba8 tiny(50, 10);
  tiny.fill(255, 255, 255);
  const ImageRgba8 before = tiny;
  app::burnCaption(tiny, {"x"}, 1);
  CHECK(tiny == before);
}

TEST_CASE("contact sheet: tiles in rows of `columns`, gaps around, the pixels of each image copied") {
  std::vector<ImageRgba8> ims(5, ImageRgba8(30, 20));
  for (std::size_t k = 0; k < ims.size(); ++k) ims[k].fill(std::uint8_t(10 * k), 0, 0);
  const ImageRgba8 sheet = app::contactSheet(ims, 3, 4);
  CHECK(sheet.width == 3 * 30 + 4 * 4);
  CHECK(sheet.height == 2 * 20 + 3 * 4);
  CHECK(sheet.at(4, 4)[0] == 0);                     // tile 0
  CHECK(sheet.at(4 + 34 * 2, 4)[0] == 20);          // tile 2: third of the first row
  CHECK(sheet.at(4 + 34, 4 + 24)[0] == 40);         // tile 4: second of the second row
  CHECK(sheet.at(2, 2)[1] == 255);                  // the gap is the background
  CHECK(app::shrinkImage(ims[1], 2).width == 15);
  CHECK(app::shrinkImage(ims[1], 2).at(3, 3)[0] == 10);
}

TEST_CASE("sweep --sheet: a contact sheet of every radius; captioned images; a bad extension refused first") {
  TempDir tmp;
  const std::string scene = (tmp.path / "s.json").string();
  std::ofstream(scene) << R"({"version": 1, "mode": "implicit2d",
    "data": {"preset": "curve2d", "count": 30}, "fit": {"kernel": "gaussian", "polynomial": "none"}})";
  const std::string dir = (tmp.path / "out").string(), sheet = (tmp.path / "sheet.png").string();
  const CliResult r = runCli("sweep " + scene + " --radii 0.05:0.6:4 --size 96x72 -o " + dir + " --sheet " + sheet);
  REQUIRE(r.rc == 0);
  CHECK(r.out.find("wrote a contact sheet of 4 images to " + sheet) != std::string::npos);
  const ImageRgba8 s = readPng(sheet);
  CHECK(s.width == 2 * 96 + 3 * 8);  // 2 columns (⌈√4⌉), 8 px gaps
  CHECK(s.height == 2 * 72 + 3 * 8);
  // Each image has its caption band: the bottom rows are darkened.
  for (const auto& e : std::filesystem::directory_iterator(dir)) {
    if (e.path().extension() != ".png") continue;
    const ImageRgba8 im = readPng(e.path().string());
    CHECK(countPixels(im, im.height - 2, im.height, 0, 90) > im.width);
  }
  CHECK(runCli("sweep " + scene + " --radii 0.05:0.6:2 --size 64x48 -o " + dir + "2 --sheet " +
               (tmp.path / "sheet.jpg").string()).rc == 2);
}
