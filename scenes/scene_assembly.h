#pragma once
// From a recipe (scenes/recipe.h) to glTF files on disk: the materials baked by the textures
// module's procedural families, the geometry, cameras, lights and sky. `svbrdf-bake scene` calls
// bake_scene; the build runs it on scenes/*.json (scenes/CMakeLists.txt).
//
// Layout of what a "scene" recipe writes into DIR:
//   DIR/NAME.gltf (+ NAME.bin when the geometry is large), DIR/textures/MATERIAL_{base_color,
//   metallic_roughness,normal}.png, DIR/sky.hdr when the recipe has a sky. The sky is named in the
//   glTF as scenes[0].extras.svbrdf.environment = "sky.hdr" (a path relative to the .gltf); glTF
//   has no standard environment, so a renderer that does not read that member renders the sun alone
//   (svbrdf-render: pass --env DIR/sky.hdr).
// What a "lod" recipe writes is in lod_scenes.h.
#include <filesystem>
#include <string>
#include <vector>

#include "gltf/writer.h"
#include "scenes/recipe.h"
#include "textures/color.h"
#include "textures/material_family.h"

namespace svbrdf {

// Bakes the recipe into out_dir (created if needed) and returns the files it wrote, the main glTF
// (or the LOD manifest) first. Every check happens before anything is written; each file is
// written atomically.
std::vector<std::filesystem::path> bake_scene(const Recipe& recipe, const std::filesystem::path& out_dir,
                                              const ColorConfig& color = ColorConfig::builtin(),
                                              const ProgressFn& progress = {});

// Shared with the LOD scenes: a procedural material's three maps written as
// DIR/textures/NAME_{base_color,metallic_roughness,normal}.png and the glTF material using them
// (added to `writer`, with its recipe in extras.svbrdf); returns the material index.
int write_material(GltfWriter& writer, const ProceduralMaterial& material, const std::string& name,
                   const std::filesystem::path& dir, std::vector<std::filesystem::path>& written);

// Texture repeats per metre for a material: 1 / (texture side in metres).
double uv_per_metre(const ProceduralMaterial& material);

// Throws svbrdf::Error naming out_dir when it exists and is not a directory or cannot be created.
void make_output_dir(const std::filesystem::path& out_dir);

}  // namespace svbrdf
