#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "render/tile_spans.h"

using namespace hermite::render;

namespace {

// How many rectangles cover each pixel of a width × height target.
std::vector<int> coverCount(const std::vector<PixelRect>& rects, int width, int height) {
  std::vector<int> count(std::size_t(width) * height, 0);
  for (const PixelRect& r : rects)
    for (int y = r.y0; y < r.y1; ++y)
      for (int x = r.x0; x < r.x1; ++x)
        if (x >= 0 && x < width && y >= 0 && y < height) ++count[std::size_t(y) * width + x];
  return count;
}

}  // namespace

TEST_CASE("tile spans: exactly the pixels of the non-empty tiles, each once, clipped to the target") {
  std::mt19937 rng(7);
  const int tile = 4;
  for (int trial = 0; trial < 40; ++trial) {
    const int width = 1 + int(rng() % 61), height = 1 + int(rng() % 47);  // not multiples of the tile
    const int tilesX = (width + tile - 1) / tile, tilesY = (height + tile - 1) / tile;
    std::vector<float> tiles(std::size_t(tilesX) * tilesY);
    const double emptyShare = (trial % 5) / 4.0;  // all full … all empty
    for (float& v : tiles) {
      const double u = double(rng()) / double(rng.max());
      v = u < emptyShare ? kEmptyTile : float(u);
    }
    if (trial % 7 == 3) tiles[0] = std::numeric_limits<float>::quiet_NaN();  // proves nothing
    const std::vector<PixelRect> rects = occupiedTileRects(tiles, tilesX, tilesY, tile, width, height);
    const std::vector<int> count = coverCount(rects, width, height);
    long long expected = 0;
    for (const PixelRect& r : rects) {
      CHECK(r.x0 < r.x1);
      CHECK(r.y0 < r.y1);
      CHECK(r.x0 >= 0);
      CHECK(r.y0 >= 0);
      CHECK(r.x1 <= width);
      CHECK(r.y1 <= height);
    }
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const float v = tiles[std::size_t(y / tile) * tilesX + x / tile];
        const int want = (v >= kEmptyTile) ? 0 : 1;
        expected += want;
        CAPTURE(x);
        CAPTURE(y);
        REQUIRE(count[std::size_t(y) * width + x] == want);
      }
    CHECK(rectPixels(rects) == expected);
    CHECK(rectTriangles(rects).size() == rects.size() * 12);
  }
}

TEST_CASE("tile spans: equal runs in consecutive tile rows merge into one rectangle") {
  // 4 × 3 tiles of 2 px, 8 × 6 px: a column of two tiles across all rows, and a run that changes.
  const float E = kEmptyTile;
  const std::vector<float> tiles = {
      0, 0, E, 1,  // bottom row
      0, 0, E, E,  //
      0, 0, E, 1,  // top row
  };
  const std::vector<PixelRect> rects = occupiedTileRects(tiles, 4, 3, 2, 8, 6);
  REQUIRE(rects.size() == 3);
  CHECK(rects[0] == PixelRect{0, 0, 4, 6});
  CHECK(rects[1] == PixelRect{6, 0, 8, 2});
  CHECK(rects[2] == PixelRect{6, 4, 8, 6});
  CHECK(rectPixels(rects) == 24 + 4 + 4);
  CHECK(occupiedTileRects(std::vector<float>(12, E), 4, 3, 2, 8, 6).empty());
}
