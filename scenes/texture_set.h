#pragma once
// Writing a procedural material as a glTF 2.0 texture set: DIR/PRESET_base_color.png (sRGB),
// DIR/PRESET_metallic_roughness.png (G roughness, B metallic), DIR/PRESET_normal.png (16-bit,
// tangent space, +Y up) and DIR/PRESET.gltf — a quad of the material's physical size (meters, in
// the XY plane facing +Z, uv (0, 0) at its top-left corner) with positions, normals, tangents and
// uvs, its buffer embedded as a data: URI, that the Khronos glTF validator passes with no error and
// no warning. Every file is written atomically; the .gltf last, so it never names missing images.
// Output is byte-identical for the same recipe.
#include <filesystem>
#include <string>

#include "gltf/writer.h"
#include "textures/material_family.h"

namespace svbrdf {

struct TextureSetFiles {
  std::filesystem::path gltf, base_color, metallic_roughness, normal;
};

// Creates dir if needed; throws svbrdf::Error naming the path when it cannot write.
TextureSetFiles write_texture_set(const ProceduralMaterial& material, const std::filesystem::path& dir,
                                  const ProgressFn& progress = {});

// generate_material + write_texture_set. Every check of the recipe happens before anything is
// written, so bad input leaves dir untouched.
TextureSetFiles bake_material(const MaterialRecipe& recipe, const std::filesystem::path& dir,
                              const ColorConfig& color = ColorConfig::builtin(), const ProgressFn& progress = {});

// The glTF of the quad (the one glTF writer, gltf/writer.h), image URIs relative to the .gltf (the
// file names of `files`).
GltfWriter material_quad_gltf(const ProceduralMaterial& material, const TextureSetFiles& files);

}  // namespace svbrdf
