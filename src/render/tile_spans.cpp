#include "render/tile_spans.h"

#include <algorithm>
#include <cstddef>

namespace hermite::render {

std::vector<PixelRect> occupiedTileRects(const std::vector<float>& tileStart, int tilesX, int tilesY, int tile,
                                         int width, int height) {
  std::vector<PixelRect> rects;
  // Rectangles that end at the top of the previous tile row: a run equal to one of them grows it.
  std::vector<std::size_t> open, nextOpen;
  for (int j = 0; j < tilesY; ++j) {
    const int y0 = j * tile, y1 = std::min((j + 1) * tile, height);
    if (y0 >= y1) break;
    nextOpen.clear();
    std::size_t scan = 0;  // open rects are in x order, as are the runs of this row
    for (int i = 0; i < tilesX;) {
      const auto empty = [&](int k) { return tileStart[std::size_t(j) * tilesX + k] >= kEmptyTile; };
      if (empty(i)) {
        ++i;
        continue;
      }
      int e = i + 1;
      while (e < tilesX && !empty(e)) ++e;
      const int x0 = i * tile, x1 = std::min(e * tile, width);
      i = e;
      if (x0 >= x1) continue;
      while (scan < open.size() && rects[open[scan]].x0 < x0) ++scan;
      if (scan < open.size() && rects[open[scan]].x0 == x0 && rects[open[scan]].x1 == x1) {
        rects[open[scan]].y1 = y1;
        nextOpen.push_back(open[scan]);
      } else {
        rects.push_back({x0, y0, x1, y1});
        nextOpen.push_back(rects.size() - 1);
      }
    }
    open.swap(nextOpen);
  }
  return rects;
}

std::vector<float> rectTriangles(const std::vector<PixelRect>& rects) {
  std::vector<float> v;
  v.reserve(rects.size() * 12);
  for (const PixelRect& r : rects) {
    const float x0 = float(r.x0), y0 = float(r.y0), x1 = float(r.x1), y1 = float(r.y1);
    for (float c : {x0, y0, x1, y0, x1, y1, x0, y0, x1, y1, x0, y1}) v.push_back(c);
  }
  return v;
}

long long rectPixels(const std::vector<PixelRect>& rects) {
  long long n = 0;
  for (const PixelRect& r : rects) n += (long long)(r.x1 - r.x0) * (r.y1 - r.y0);
  return n;
}

}  // namespace hermite::render
