#include "apps/render_merge.h"

#include <algorithm>
#include <cstdio>
#include <optional>
#include <tuple>

#include "apps/render_frames.h"
#include "base/error.h"
#include "textures/color.h"
#include "textures/image.h"

namespace svbrdf {

namespace fs = std::filesystem;

namespace {

std::string pixel_text(long long x, long long y) { return "(" + std::to_string(x) + ", " + std::to_string(y) + ")"; }

std::string size_text(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

}  // namespace

RenderLayers merge_tiles(const std::vector<fs::path>& tiles) {
  if (tiles.empty()) throw input_error("--merge", "no tiles given");
  RenderLayers frame;
  std::vector<int> owner;  // per pixel of the frame, the tile that holds it, or -1
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const std::string where = tiles[t].string();
    std::error_code ec;
    if (!fs::exists(tiles[t], ec)) throw input_error(where, "no such tile (not rendered yet, or its task failed?)");
    const ExrImage tile = read_exr(tiles[t]);
    const FrameWindow& w = tile.window;
    if (t == 0) {
      if (w.frame_width < 1 || w.frame_height < 1) throw input_error(where, "its frame (display window) is empty");
      check_image_size(where + ": its frame", w.frame_width, w.frame_height, int(tile.names.size()));
      frame.image = Image(w.frame_width, w.frame_height, tile.image.channels);
      frame.names = tile.names;
      frame.frame = {0, 0, w.frame_width, w.frame_height};
      owner.assign(std::size_t(w.frame_width) * std::size_t(w.frame_height), -1);
    } else if (w.frame_width != frame.frame.frame_width || w.frame_height != frame.frame.frame_height) {
      throw input_error(where, "is a tile of a " + size_text(w.frame_width, w.frame_height) + " frame, " + tiles[0].string() +
                                   " of a " + size_text(frame.frame.frame_width, frame.frame.frame_height) + " one");
    } else if (tile.names != frame.names) {
      throw input_error(where, "has other channels than " + tiles[0].string() + " (rendered with other --aov?)");
    }
    // Half channels would have rounded the render's floats: the PNG made from them would not be the
    // single render's.
    for (std::size_t c = 0; c < tile.formats.size(); ++c)
      if (tile.formats[c] != PixelFormat::float32)
        throw input_error(where, "stores channel " + tile.names[c] +
                                     " in less than float; a tile must be the float EXR that svbrdf-render --tile writes");
    const long long x0 = w.x, y0 = w.y, x1 = x0 + tile.image.width, y1 = y0 + tile.image.height;
    if (x0 < 0 || y0 < 0 || x1 > w.frame_width || y1 > w.frame_height)
      throw input_error(where, "its pixels " + pixel_text(x0, y0) + " to " + pixel_text(x1, y1) + " reach past its " +
                                   size_text(w.frame_width, w.frame_height) + " frame");
    const std::size_t channels = std::size_t(frame.image.channels);
    for (long long y = y0; y < y1; ++y)
      for (long long x = x0; x < x1; ++x) {
        const std::size_t p = std::size_t(y) * std::size_t(w.frame_width) + std::size_t(x);
        if (owner[p] >= 0)
          throw input_error(where, "overlaps " + tiles[std::size_t(owner[p])].string() + " at pixel " + pixel_text(x, y));
        owner[p] = int(t);
        const std::size_t q = (std::size_t(y - y0) * std::size_t(tile.image.width) + std::size_t(x - x0)) * channels;
        std::copy_n(tile.image.pixels.begin() + std::ptrdiff_t(q), channels,
                    frame.image.pixels.begin() + std::ptrdiff_t(p * channels));
      }
  }
  for (std::size_t p = 0; p < owner.size(); ++p)
    if (owner[p] < 0) {
      const long long x = (long long)(p % std::size_t(frame.image.width)), y = (long long)(p / std::size_t(frame.image.width));
      throw input_error("--merge", "pixel " + pixel_text(x, y) + " of the " + size_text(frame.image.width, frame.image.height) +
                                       " frame is in none of the " + std::to_string(tiles.size()) +
                                       " tiles given (a tile is missing)");
    }
  return frame;
}

void run_merge(const RenderCommand& c, const std::vector<fs::path>& tiles, const char* program) {
  if (c.out.empty()) throw input_error("--merge", "needs -o/--out: the EXR of the whole frame");
  const ColorConfig color = ColorConfig::resolve(c.ocio.empty() ? std::nullopt : std::optional<fs::path>(c.ocio));
  OutputOptions oo = c.output_options();
  oo.tile = false;  // the merge of tiles is the frame
  std::tie(oo.display, oo.view) = color.display_view(c.display, c.view);
  // One frame's tiles into its outputs.
  const auto merge = [&](const OutputOptions& out, const std::vector<fs::path>& parts) {
    // The tiles are read before anything is written: a refused tile leaves the outputs as they were.
    prepare_outputs(out);
    for (const fs::path& t : parts)
      if (t.lexically_normal() == out.exr.lexically_normal())
        throw input_error(out.exr.string(), "is both a tile and the output");
    write_layers(merge_tiles(parts), out, color);
    if (!c.quiet)
      std::fprintf(stderr, "%s: merged %zu tiles into %s\n", program, parts.size(), out.exr.string().c_str());
  };
  if (c.frames.empty()) return merge(oo, tiles);
  // --frames: each frame's tiles and outputs are named as the render names them (apps/render_frames.h).
  const FrameRange range = parse_frames(c.frames);
  for (int f = range.first;; ++f) {
    OutputOptions out = oo;
    out.exr = frame_path(c.out, f, "--out");
    if (!c.png.empty()) out.png = frame_path(c.png, f, "--png");
    std::vector<fs::path> parts;
    for (const fs::path& t : tiles) parts.emplace_back(frame_path(t.string(), f, "a tile"));
    merge(out, parts);
    if (f == range.last) break;
  }
}

}  // namespace svbrdf
