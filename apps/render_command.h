#pragma once
// svbrdf-render's command line: its options as values, their definitions, and the render they ask
// for. The program (render_main.cpp) and the Python module's render() (python/) parse the same
// options with the same checks and render through these same steps, so one scene and one set of
// options give the same image and the same one-line refusals from either.
#include <CLI/CLI.hpp>

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "apps/mip_cache_options.h"
#include "base/resource_limits.h"
#include "render/output.h"
#include "render/renderer.h"

namespace svbrdf {

struct RenderCommand {
  std::string scene_file, out, png, res, camera, env, sun, filter = "brdf", light_sampling = "mis", ocio,
      light_units = "photometric", normal_mapping = "shading", variant, display, view, crop, tile, frames;
  int spp = 64, threads = 0, max_depth = 16;
  std::uint64_t seed = 0, max_texels = resource_limits().max_texels;
  double time_limit = 0.0;
  double fps = 0.0;  // 0: not given (kDefaultFps, apps/render_frames.h)
  float exposure = 0.0f, footprint_scale = 0.0f, clamp = 0.0f, aperture = 0.0f, focus_distance = 0.0f;
  bool use_float = false, quiet = false, aovs = false, transparent = false;
  MipCacheOptions mip_cache;
  // --texture-cache [MB]: the level-0 textures out of core (render/texture_tiles.h), with at most MB
  // megabytes of their tiles in memory; absent: the images are held in memory whole.
  std::optional<std::string> texture_cache;
  // Positionals after the scene: the rest of the tiles for svbrdf-render --merge (apps/render_merge.h);
  // a render refuses them. Defined here, so that the program and the module parse alike.
  std::vector<std::string> more_inputs;

  // Defines every option of svbrdf-render on `app`, bound to the members above.
  void add_options(CLI::App& app);
  // The outputs these options ask for (OCIO's display and view not yet resolved). Throws bad input
  // for an --out that is not an .exr file.
  OutputOptions output_options() const;
};

// --texture-cache's megabytes (TextureTiles::kDefaultMegabytes when given without a number), or
// nullopt when it is absent. Throws bad input naming the option for a value that is not a number in
// [TextureTiles::kMinMegabytes, 1e9].
std::optional<double> texture_cache_megabytes(const std::optional<std::string>& text);

struct RenderOutcome {
  Film film{0, 0};
  RenderStats stats;
  int status = 0;  // 0, or 128 + the signal that stopped the render
};

// Renders `scene` as `command` asks, printing what svbrdf-render prints on stderr under the name
// `program`. With --frames, each frame in turn into its own files (apps/render_frames.h); the outcome
// is the last frame's. The EXR and PNG are written when command.out names the EXR (the program gives it a
// default; the Python module, which returns the film, leaves it empty unless asked). Throws
// svbrdf::Error for bad input and failures, with the program's lines. `cancel` stops the render once
// set (the program's is the flag its signal handler sets, interrupt_requested(); the Python module
// sets its own when Python sees a Ctrl-C); the render then returns what accumulated.
RenderOutcome run_render(RenderCommand& command, const std::filesystem::path& scene, const char* program,
                         const std::atomic<bool>& cancel);

}  // namespace svbrdf
