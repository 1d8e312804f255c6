#pragma once
// A part of the frame rendered alone: a crop window (--crop) or one tile of an even split (--tile),
// for renders spread over machines and assembled afterwards (apps/render_merge.h). Every pixel of a
// crop is the same bit for bit as in a render of the whole frame with the same seed: a sample's
// random numbers depend only on (seed, its pixel in the frame, its index), and nothing a pixel gets
// depends on another pixel (renderer.h).
#include <string>

namespace svbrdf {

// A rectangle of the frame's pixels, half-open: columns [x0, x1), rows [y0, y1).
struct PixelRect {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
  bool empty() const { return x1 <= x0 || y1 <= y0; }
  bool operator==(const PixelRect&) const = default;
};

// Tile `index` of `count` (0 ≤ index < count ≤ height) of a width × height frame: horizontal bands
// of whole rows, band i the rows [⌊i·height/count⌋, ⌊(i+1)·height/count⌋), so the bands differ by
// at most one row and cover the frame once. Bands, not a grid: any count splits evenly, and each
// band is whole scanlines of the EXR.
PixelRect tile_rect(int index, int count, int width, int height);

// "--crop x0,y0,x1,y1" (pixels, half-open, within width × height and not empty) as a rectangle.
// Throws svbrdf::Error (bad input) naming `option` and the text.
PixelRect parse_crop(const std::string& text, int width, int height, const std::string& option = "--crop");

// "--tile I/N" (I in 0..N-1, N ≥ 1 and at most the frame's rows) as tile_rect's rectangle.
// Throws svbrdf::Error (bad input) naming `option` and the text.
PixelRect parse_tile(const std::string& text, int width, int height, const std::string& option = "--tile");

}  // namespace svbrdf
