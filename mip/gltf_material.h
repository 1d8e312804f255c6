#pragma once
// The level-0 texels of one material of a glTF 2.0 file (.gltf or .glb), for
// `svbrdf-bake mip SCENE.gltf --material NAME|INDEX`: its baseColor, metallicRoughness, normal,
// specular and specular colour textures and factors, its ior and its clear coat (weight, roughness and
// normal textures and factors), decoded as textures/material_loader.h defines (sRGB base color through
// OCIO). Images may be files beside the glTF, data: URIs or buffer views. Texture transforms and
// texCoord sets are ignored: the MIP build works on the images' own texel grid.
#include <filesystem>
#include <functional>
#include <string>

#include "gltf/material_desc.h"
#include "textures/color.h"
#include "textures/material_loader.h"
#include "textures/material_texels.h"

namespace svbrdf {

// What decode_material_texels reads of a glTF material: its textures' images (by `image_of`, which
// returns the image of a present slot and whether it is already scene-linear; `color` says the slot
// holds sRGB-encoded colour) and its factors, each image named `prefix` + its JSON path. The one
// mapping of a glTF material to MIP texels, for the renderer (render/material_mips.h) and the bake.
// Why the MIP's lobes cannot stand for this material's BRDF, naming the extension (empty: they
// can). The renderer shades such a material with level-0 lookups under every filter and says so;
// the bake refuses it.
std::string mip_unsupported(const MaterialDesc& m);

struct SlotImage {
  const Image* image = nullptr;
  bool linear = false;
};
MaterialImages material_images(const MaterialDesc& d, const std::function<SlotImage(const TextureRef&, bool color)>& image_of,
                               const std::string& prefix = "");

// `material` is a material's name or, when it is all digits, its index. Throws svbrdf::Error naming
// the file and the JSON path for a missing file, an unknown material, a missing or undecodable image.
MaterialTexels load_gltf_material_texels(const std::filesystem::path& gltf, const std::string& material,
                                         const ColorConfig& color = ColorConfig::builtin());

}  // namespace svbrdf
