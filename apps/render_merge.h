#pragma once
// svbrdf-render --merge: the tiles of a frame (--tile, --crop: render/crop.h), rendered on as many
// machines, assembled into the frame's EXR and PNG, the same bit for bit as one render of the whole
// frame with the same seed and options writes. The tiles hold the render's floats (render/output.h);
// the merge places each by its data window and writes through the render's own output path, with
// the same output options (--png, --float, --exposure, --transparent, --ocio-config, --display, --view).
#include <filesystem>
#include <string>
#include <vector>

#include "apps/render_command.h"
#include "render/output.h"

namespace svbrdf {

// The frame the tiles make. Each must be an EXR tile of the same frame (display window) with the same
// channels stored in float, and together they must cover the frame exactly once. Throws svbrdf::Error
// (bad input) in one line naming the tile that is missing, unreadable, corrupt, of another frame or
// channels, or overlaps another, or the first pixel no tile covers.
RenderLayers merge_tiles(const std::vector<std::filesystem::path>& tiles);

// Merges `tiles` and writes command.out and its PNG as run_render would, printing on stderr under
// the name `program` unless command.quiet. With command.frames, merges each frame of the range: the
// tiles and the outputs named for the frame as --frames names a render's (apps/render_frames.h).
void run_merge(const RenderCommand& command, const std::vector<std::filesystem::path>& tiles, const char* program);

}  // namespace svbrdf
