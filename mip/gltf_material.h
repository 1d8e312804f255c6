#pragma once
// The level-0 texels of one material of a glTF 2.0 file (.gltf or .glb), for
// `svbrdf-bake mip SCENE.gltf --material NAME|INDEX`: its baseColor, metallicRoughness and normal
// textures and factors, decoded as textures/material_loader.h defines (sRGB base color through
// OCIO). Images may be files beside the glTF, data: URIs or buffer views. Texture transforms and
// texCoord sets are ignored: the MIP build works on the images' own texel grid.
#include <filesystem>
#include <string>

#include "textures/color.h"
#include "textures/material_texels.h"

namespace svbrdf {

// `material` is a material's name or, when it is all digits, its index. Throws svbrdf::Error naming
// the file and the JSON path for a missing file, an unknown material, a missing or undecodable image.
MaterialTexels load_gltf_material_texels(const std::filesystem::path& gltf, const std::string& material,
                                         const ColorConfig& color = ColorConfig::builtin());

}  // namespace svbrdf
