#pragma once
// The scene's textures ready for lookups at shading time, through the textures module: color images
// (base color, emissive, specular color) converted sRGB → scene-linear once by its OpenColorIO
// config, data images kept raw; lookups by its sampler (textures/sampler.h) with the glTF sampler's
// wrap modes and the slot's KHR_texture_transform. The `level0` filter of issue 6 is the nearest
// texel at the exact uv. Allocation-free and thread-safe after construction.
#include <vector>

#include <glm/glm.hpp>

#include "render/scene.h"
#include "textures/color.h"

namespace svbrdf {

class TextureSet {
 public:
  TextureSet(const Scene& scene, const ColorConfig& color = ColorConfig::builtin());

  // The slot's texture at `uv` (the primitive's TEXCOORD_n, before the slot's transform); RGBA with
  // gray expanded and a missing alpha read as 1. `color` selects the linearized copy.
  glm::vec4 lookup(const TextureRef& ref, glm::vec2 uv, bool color) const {
    const Prepared& p = textures_[static_cast<std::size_t>(ref.texture)];
    const Image& image = color && p.linear ? *p.linear : *p.raw;
    return sample(image, p.sampler, ref.transform.apply(uv));
  }

  // The image a slot reads: the linearized copy when `color` and one exists, else as stored.
  const Image& image(const TextureRef& ref, bool color) const {
    const Prepared& p = textures_[static_cast<std::size_t>(ref.texture)];
    return color && p.linear ? *p.linear : *p.raw;
  }
  // Whether image(ref, true) is a linearized copy (color slots have one).
  bool linearized(const TextureRef& ref) const { return textures_[static_cast<std::size_t>(ref.texture)].linear != nullptr; }
  // The texture's sampler (its wrap modes; the filter is nearest).
  const Sampler& sampler(const TextureRef& ref) const { return textures_[static_cast<std::size_t>(ref.texture)].sampler; }

  // Texture size in texels (for footprints and the MIP-level AOV).
  glm::ivec2 size(const TextureRef& ref) const {
    const Image& im = *textures_[static_cast<std::size_t>(ref.texture)].raw;
    return {im.width, im.height};
  }

 private:
  struct Prepared {
    const Image* raw = nullptr;
    const Image* linear = nullptr;  // null unless a color slot uses the image
    Sampler sampler;                // nearest, with the texture's wrap modes
  };
  std::vector<Image> linear_images_;  // per scene image; empty when no color slot uses it
  std::vector<Prepared> textures_;     // per scene texture
};

}  // namespace svbrdf
