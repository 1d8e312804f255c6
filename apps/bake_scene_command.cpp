// `svbrdf-bake scene RECIPE [--ocio-config FILE] --out DIR`: a scene recipe (scenes/*.json) baked into
// glTF scenes with their textures (scenes/scene_assembly.h, scenes/lod_scenes.h). Prints the files
// written, the main one first
// (none with --quiet, as the build runs it).
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "apps/bake_commands.h"
#include "base/output_location.h"
#include "scenes/recipe.h"
#include "scenes/scene_assembly.h"
#include "textures/color.h"

namespace svbrdf {

namespace {

struct SceneOptions {
  std::string recipe, out, ocio_config;
  bool quiet = false;
};

void run(const SceneOptions& o) {
  const ColorConfig color =
      ColorConfig::resolve(o.ocio_config.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.ocio_config));
  const Recipe recipe = read_recipe(o.recipe);  // every check before anything is written
  check_output_folder(o.out);
  const auto start = std::chrono::steady_clock::now();
  const ProgressFn progress = [&](std::string_view stage) {
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!o.quiet && t > 1.0)
      std::fprintf(stderr, "svbrdf-bake: scene %s: %.*s (%.1f s)\n", o.recipe.c_str(), int(stage.size()), stage.data(), t);
  };
  const auto files = bake_scene(recipe, o.out, color, progress);
  if (!o.quiet)
    for (const auto& f : files) std::printf("%s\n", f.string().c_str());
}

}  // namespace

void add_scene_command(CLI::App& app) {
  auto options = std::make_shared<SceneOptions>();
  CLI::App* cmd = app.add_subcommand("scene", "Bake a scene recipe (scenes/*.json) into glTF scenes with their textures");
  cmd->add_option("RECIPE", options->recipe, "recipe file (kind \"scene\" or \"lod\"; see scenes/README.md)")->required();
  cmd->add_option("--ocio-config", options->ocio_config, "OpenColorIO config to use instead of $OCIO or the built-in one");
  cmd->add_option("--out", options->out, "output directory (created if missing)")->required();
  cmd->add_flag("-q,--quiet", options->quiet, "print nothing (no progress lines, no file list)");
  cmd->callback([options] { run(*options); });
}

}  // namespace svbrdf
