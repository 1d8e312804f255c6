#pragma once
// What enters one material's level-0 texels (MaterialTexels, decoded by decode_material_texels from
// the material's images and factors, textures/material_loader.h), listed in one place. SceneMips
// puts the listed textures on one texel grid and shares one build between materials whose lists are
// equal (render/material_mips.h), and the MIP
// cache's key hashes the list (render/mip_cache_key.h), so the two cannot disagree about what makes
// two builds the same.
//
// A new input of the texels — a factor or a texture that the decode reads (mip/gltf_material.h
// material_images maps the material to them) — is one more entry in texel_inputs() (texel_inputs.cpp);
// the grid, the sharing and the cache key follow it.
#include <string>
#include <vector>

#include "gltf/material_desc.h"

namespace svbrdf {

struct TexelInput {
  std::string name;                     // the glTF name: "baseColorFactor", "normalTexture"
  const TextureRef* texture = nullptr;  // a texture slot of the material (null for a factor)
  bool color = false;                   // the slot's image is decoded as color (sRGB → linear)
  std::vector<float> values;            // a factor's components (empty for a texture slot)
};

// The inputs of `material`'s texels, in a fixed order; texture slots point into `material`.
std::vector<TexelInput> texel_inputs(const MaterialDesc& material);

// Whether two texture transforms are the same.
bool same_transform(const TextureTransform& a, const TextureTransform& b);

// Whether two materials' texels and the way their textures are looked up (uv set, transform) are the
// same: equal factors and the same textures read alike.
bool same_texels(const MaterialDesc& a, const MaterialDesc& b);

}  // namespace svbrdf
