#pragma once
// The subcommands of svbrdf-bake, each registered by its own unit so the material bakes (textures
// work) and the MIP commands (mip work) grow independently. A command's callback runs inside
// CLI::App::parse and reports bad input by throwing svbrdf::Error.
namespace CLI {
class App;
}

namespace svbrdf {

// `svbrdf-bake material PRESET ...`: procedural texture sets and their glTF quad.
void add_material_command(CLI::App& app);
// `svbrdf-bake mip | eval | compare`: ../shared/spec/brdf-mip.md, "svbrdf-bake surface".
void add_mip_commands(CLI::App& app);
// `svbrdf-bake random-family`: the BRDF MIP's error distribution over the random material family.
void add_random_family_command(CLI::App& app);
// `svbrdf-bake scene RECIPE --out DIR`: scene recipes (scenes/*.json) into glTF scenes.
void add_scene_command(CLI::App& app);

}  // namespace svbrdf
