#pragma once
// Which pixels the baked trace pass must run on. The tile pass (trace_tile_pass.glsl) proves,
// per tile of `tile`² pixels, how far every ray of the tile is free of zeros; a tile whose cone
// leaves the bounds without meeting one (value ≥ kEmptyTile) is background in every pixel. The
// trace pass then draws rectangles over the other tiles only: llvmpipe runs every instruction of
// a fragment shader for every covered pixel (an `if` only masks lanes; a loop runs at least once),
// so pixels that are not drawn are the only ones that cost nothing.
//
// No GL here: the tile values come from a read-back, the rectangles go to a vertex buffer.

#include <vector>

namespace hermite::render {

// Tile-pass value of a tile none of whose rays meets a zero inside the bounds.
constexpr float kEmptyTile = 1e30f;

// A rectangle of pixels in GL window coordinates (x right, y up, origin at the bottom-left corner
// of the target), [x0, x1) × [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  bool operator==(const PixelRect&) const = default;
};

// Rectangles that together cover every pixel of the tiles not proven empty, each pixel once.
// `tileStart` holds tilesX × tilesY values, row 0 at the bottom (GL order); tile (i, j) covers
// pixels [i·tile, (i+1)·tile) × [j·tile, (j+1)·tile) clipped to width × height. Runs of non-empty
// tiles in a tile row become one rectangle; a run equal to the one in the row below extends it.
// A NaN value counts as non-empty (nothing proven).
std::vector<PixelRect> occupiedTileRects(const std::vector<float>& tileStart, int tilesX, int tilesY, int tile,
                                         int width, int height);

// Two triangles per rectangle as (x, y) pixel-corner coordinates: 12 floats per rectangle.
std::vector<float> rectTriangles(const std::vector<PixelRect>& rects);

// Pixels the rectangles cover (for the bench and tests).
long long rectPixels(const std::vector<PixelRect>& rects);

}  // namespace hermite::render
