#pragma once
// The procedural material families: sandstone, painted-wall, printed-paper, metal-tray,
// granite. Each is deterministic for a seed, has a physical scale (mm per texel; features keep
// their size in mm whatever the texture size) and variants, and yields glTF metallic-roughness
// parameters. Normals always come from a height field in mm (textures/height_field.h), so bump
// heights and spacings are physical. Textures tile (all noise is periodic over the texture).
//
// What generate_material returns is the texture set *as stored*: the encoded images (sRGB base
// color, metallic-roughness with roughness in G and metallic in B, normal map) quantized to the
// bit depth they are written with, and the MaterialTexels decoded from them exactly as
// load_material_texels decodes the written files. So a MIP build from memory and one from the
// baked files see the same level 0.
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "textures/color.h"
#include "textures/image.h"
#include "textures/material_texels.h"

namespace svbrdf {

struct MaterialPreset {
  std::string_view name;                   // "metal-tray"
  std::string_view summary;                // one line for --help and listings
  std::vector<std::string_view> variants;  // the first is the default
  double mm_per_texel;                     // default physical scale
};

// All presets, in a fixed order.
std::span<const MaterialPreset> material_presets();
// Throws svbrdf::Error listing the known names for an unknown preset.
const MaterialPreset& find_material_preset(std::string_view name);

struct MaterialRecipe {
  std::string preset;
  std::string variant;         // empty: the preset's default
  int size = 1024;             // texels per side; a power of two in [1, kMaxMaterialSize]
  std::uint64_t seed = 1;
  double mm_per_texel = 0.0;   // 0: the preset's (and variant's) default
};
inline constexpr int kMaxMaterialSize = 16384;

// Called at each stage of a bake ("pattern", "normals", "encoding", "writing ..."); may be empty.
using ProgressFn = std::function<void(std::string_view stage)>;

struct ProceduralMaterial {
  std::string preset, variant;
  std::uint64_t seed = 0;
  double mm_per_texel = 0.0;
  MaterialTexels texels;            // decoded from the stored images (see above)
  std::vector<float> height_mm;     // the height field the normals come from, row-major from the top
  Image base_color;                 // sRGB-encoded RGB, as stored
  Image metallic_roughness;         // R = 1 (unused, reads as no occlusion), G = roughness, B = metallic
  Image normal;                     // encode_normal of the unit normals
  PixelFormat base_color_format = PixelFormat::uint8;
  PixelFormat metallic_roughness_format = PixelFormat::uint8;
  PixelFormat normal_format = PixelFormat::uint16;

  double side_mm() const { return texels.width * mm_per_texel; }
};

// Validates the recipe (throws svbrdf::Error for an unknown preset or variant, a size that is not
// a power of two or out of range, a non-positive scale) and generates the material.
ProceduralMaterial generate_material(const MaterialRecipe& recipe, const ColorConfig& color = ColorConfig::builtin(),
                                     const ProgressFn& progress = {});

// The stored images of square level-0 texels `raw` (its base colour, metallic, roughness and normal:
// the sRGB base colour, metallic-roughness and normal map) in `out`'s formats, quantized to them, and
// out.texels as a reader decodes those images back: generate_material's last step, for texels made
// elsewhere (the random family's, written as files by bench/mip/random_texture_set.cpp).
void store_material_images(const MaterialTexels& raw, const ColorConfig& color, ProceduralMaterial& out);

// The default mm per texel of a preset's variant (variants may differ: halftone print is finer).
double default_mm_per_texel(std::string_view preset, std::string_view variant);

}  // namespace svbrdf
