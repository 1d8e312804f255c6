#pragma once
// Writing a render: the radiance as linear OpenEXR RGBA (half by default, float on request; no
// exposure applied; alpha and premultiplied colour as Film::alpha says), with the AOVs as layers of
// the same file when asked for, and a display-referred PNG beside it (RGBA with straight alpha for a
// transparent background). The two are written as one set: each is encoded and written to its
// temporary first, and only when both are complete are they renamed into place
// (base/atomic_file.h), so a failure leaves no new file and never an EXR that does not match its PNG.
//
// A tile (a crop of the frame, render/crop.h) is written as the EXR alone, every channel in float,
// its data window the crop inside the frame's display window: the merge of the tiles
// (apps/render_merge.h) reads back the very floats a render of the whole frame holds and writes the
// EXR and PNG through write_layers below, so they are that render's bit for bit. A PNG of one tile
// would show a fragment no viewer places in its frame; the PNG is the merge's.
#include <filesystem>
#include <string>
#include <vector>

#include "render/renderer.h"
#include "textures/color.h"

namespace svbrdf {

struct OutputOptions {
  std::filesystem::path exr;
  std::filesystem::path png;  // empty: beside the EXR with the same stem
  bool float32 = false;
  float exposure = 0.0f;      // stops, PNG only
  bool transparent = false;   // the PNG has alpha (the render's background was not drawn)
  std::string display, view;  // the PNG's OCIO display and view; empty: the config's defaults
  // Layers of the EXR: albedo.R/G/B, N.X/Y/Z (the shading normal), Z (depth, float) and mip_level.X.
  bool aovs = false;
  bool tile = false;  // a tile for the merge: the EXR alone, in float, placed in its frame
};

// A render's EXR channels as floats, in the order the EXR stores them: R, G, B, A (the radiance
// premultiplied by alpha, Film::alpha), then with AOVs albedo.R/G/B, N.X/Y/Z, Z, mip_level.X; and
// where the image lies in its frame.
struct RenderLayers {
  Image image;
  std::vector<std::string> names;
  FrameWindow frame;
};
RenderLayers render_layers(const Film& film, bool aovs);

// Every file write_outputs writes: the EXR and, unless a tile, the PNG.
std::vector<std::filesystem::path> output_paths(const OutputOptions& options);

// Before rendering: each output's folder exists (created if missing) and takes a new file, no output
// path names a folder, and the temporaries a killed run left beside them are removed
// (base/output_location.h). Throws bad input for a wrong path, Error::Kind::environment for a folder
// the machine will not let us write.
void prepare_outputs(const OutputOptions& options);

void write_outputs(const Film& film, const OutputOptions& options, const ColorConfig& color = ColorConfig::builtin());
// write_outputs of channels already gathered (render_layers' names; the first four R, G, B, A).
void write_layers(const RenderLayers& layers, const OutputOptions& options, const ColorConfig& color = ColorConfig::builtin());

// Scene-linear → display values: 2^exposure, then the config's display and view (empty: its defaults).
Image to_display(const Image& linear, float exposure, const ColorConfig& color = ColorConfig::builtin(),
                 const std::string& display = {}, const std::string& view = {});

}  // namespace svbrdf
