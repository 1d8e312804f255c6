#pragma once
// The scene's textures ready for lookups at shading time: color images (base color, emissive,
// specular color) converted sRGB → linear once, data images kept raw. Lookups are the `level0`
// filter of issue 6: the nearest texel at the exact uv, with the sampler's wrap modes and the slot's
// KHR_texture_transform. Allocation-free and thread-safe after construction.
//
// A stand-in until the textures module's sampler and OpenColorIO config are in main (issue 4):
// then the conversion goes through its ColorConfig and the lookup through its sample().
#include <vector>

#include <glm/glm.hpp>

#include "render/scene.h"

namespace svbrdf {

class TextureSet {
 public:
  explicit TextureSet(const Scene& scene);

  // The slot's texture at `uv` (the primitive's TEXCOORD_n, before the slot's transform); RGBA with
  // gray expanded and a missing alpha read as 1. `color` selects the linearized copy.
  glm::vec4 lookup(const TextureRef& ref, glm::vec2 uv, bool color) const;

  // Texture size in texels (for footprints and the MIP-level AOV).
  glm::ivec2 size(const TextureRef& ref) const;

 private:
  struct Prepared {
    const Image* raw = nullptr;
    Image linear;  // empty unless a color slot uses the image
  };
  const Scene& scene_;
  std::vector<Prepared> images_;
};

// IEC 61966-2-1 sRGB decoding (stand-in for the OCIO path; same numbers: 0.5 → 0.214041).
float srgb_to_linear(float c);

}  // namespace svbrdf
