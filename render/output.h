#pragma once
// Writing a render: the radiance as linear OpenEXR (half by default, float on request; no exposure
// applied), a display-referred PNG beside it, and optional AOVs, each written atomically.
#include <filesystem>

#include "render/renderer.h"
#include "textures/color.h"

namespace svbrdf {

struct OutputOptions {
  std::filesystem::path exr;
  std::filesystem::path png;  // empty: beside the EXR with the same stem
  bool float32 = false;
  float exposure = 0.0f;      // stops, PNG only
  bool aovs = false;          // <stem>.albedo.exr, .normal.exr, .depth.exr, .level.exr
};

void write_outputs(const Film& film, const OutputOptions& options, const ColorConfig& color = ColorConfig::builtin());

// Scene-linear → display values: 2^exposure, then the config's default display and view.
Image to_display(const Image& linear, float exposure, const ColorConfig& color = ColorConfig::builtin());

}  // namespace svbrdf
