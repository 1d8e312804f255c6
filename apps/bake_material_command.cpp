// `svbrdf-bake material PRESET [--variant V] [--size N] [--seed S] [--mm-per-texel X]
// [--ocio-config FILE] --out DIR`: a procedural material's glTF texture set (scenes/texture_set.h).
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "base/cli_checks.h"
#include "apps/bake_commands.h"
#include "base/output_location.h"
#include "textures/color.h"
#include "textures/material_family.h"
#include "scenes/texture_set.h"

namespace svbrdf {

namespace {

struct MaterialOptions {
  std::string preset, variant, out, ocio_config;
  int size = 1024;
  std::uint64_t seed = 1;
  double mm_per_texel = 0.0;
};

std::string preset_listing() {
  std::string s = "Presets (variants, the first is the default):";
  for (const MaterialPreset& p : material_presets()) {
    s += "\n  ";
    s += p.name;
    s += " (";
    for (std::size_t i = 0; i < p.variants.size(); ++i) {
      if (i) s += ", ";
      s += p.variants[i];
    }
    s += "): ";
    s += p.summary;
  }
  return s;
}

void run(const MaterialOptions& o) {
  const ColorConfig color =
      ColorConfig::resolve(o.ocio_config.empty() ? std::nullopt : std::optional<std::filesystem::path>(o.ocio_config));
  MaterialRecipe recipe{o.preset, o.variant, o.size, o.seed, o.mm_per_texel};
  check_output_folder(o.out);  // before the bake: its seconds must not end in "cannot write"
  // A progress line per stage, once a bake has taken more than a second.
  const auto start = std::chrono::steady_clock::now();
  const auto elapsed = [start] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(); };
  const std::string label = o.preset + " " + std::to_string(o.size) + "x" + std::to_string(o.size);
  const ProgressFn progress = [&](std::string_view stage) {
    if (const double t = elapsed(); t > 1.0)
      std::fprintf(stderr, "svbrdf-bake: material %s: %.*s (%.1f s)\n", label.c_str(), int(stage.size()), stage.data(), t);
  };
  const TextureSetFiles files = bake_material(recipe, o.out, color, progress);
  if (const double t = elapsed(); t > 1.0) std::fprintf(stderr, "svbrdf-bake: material %s: done (%.1f s)\n", label.c_str(), t);
  std::printf("%s\n", files.gltf.string().c_str());
}

}  // namespace

void add_material_command(CLI::App& app) {
  auto options = std::make_shared<MaterialOptions>();
  CLI::App* cmd = app.add_subcommand("material", "Bake a procedural material into a glTF texture set (PNG maps + PRESET.gltf quad)");
  cmd->footer(preset_listing());
  cmd->add_option("PRESET", options->preset, "sandstone | painted-wall | printed-paper | metal-tray | granite")->required();
  cmd->add_option("--variant", options->variant, "variant of the preset (default: its first)");
  cmd->add_option("--size", options->size, "texels per side, a power of two up to " + std::to_string(kMaxMaterialSize) + " (default 1024)")
      ->check(cli::whole_in(1, kMaxMaterialSize));
  cmd->add_option("--seed", options->seed, "random seed; the same seed gives byte-identical files (default 1)")
      ->check(cli::unsigned_whole);
  cmd->add_option("--mm-per-texel", options->mm_per_texel, "physical scale, in (0, 1000] (default: the preset's)")
      ->check(cli::number_in(0.0, 1000.0, true, false));
  cmd->add_option("--ocio-config", options->ocio_config, "OpenColorIO config to use instead of $OCIO or the built-in one");
  cmd->add_option("--out", options->out, "output directory (created if missing)")->required();
  cmd->callback([options] { run(*options); });
}

}  // namespace svbrdf
