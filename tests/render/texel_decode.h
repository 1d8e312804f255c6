#pragma once
// What the tests of an extension's level-0 texels (textures/material_loader.h) share: the extension's
// texture in a scene of its own, decoded as the MIP builds take it (material_images over
// TextureSet::image), the point the renderer shades at a texel's centre, and a refused decode.
#include <gtest/gtest.h>

#include <string>
#include <utility>

#include "appearance/frame.h"
#include "base/error.h"
#include "gltf/scene.h"
#include "mip/gltf_material.h"
#include "render/surface.h"
#include "render/texture_set.h"
#include "textures/material_loader.h"

namespace svbrdf::texel_decode {

// A scene whose texture 0 is `pixels` (images[0]); materials are the caller's.
inline Scene one_image_scene(Image pixels) {
  Scene s;
  ImageDesc im;
  im.where = "images[0]";
  im.pixels = std::move(pixels);
  s.images.push_back(std::move(im));
  TextureDesc t;
  t.image = 0;
  s.textures.push_back(t);
  return s;
}

// `m`'s texels from the images TextureSet holds, as SceneMips hands them to the decode (the slot's
// `color` picks the linearized copy where there is one).
inline MaterialTexels decode_as_built(const MaterialDesc& m, const TextureSet& textures) {
  return decode_material_texels(
      material_images(m, [&](const TextureRef& r, bool color) { return SlotImage{&textures.image(r, color), false}; }));
}

// The point of `m` at the centre of texel (i, j) of a w×h texture on uv set 0 (the level0 lookup
// reads that texel), on a surface whose shading frame is the tangent frame: the renderer's tangent-
// space quantities are then the texels'.
inline SurfacePoint texel_centre(const MaterialDesc& m, int i, int j, int w, int h) {
  SurfacePoint sp;
  sp.material = &m;
  sp.tangent = glm::vec3(1.0f, 0.0f, 0.0f);
  sp.shading = Frame::from_normal_tangent(glm::vec3(0.0f, 0.0f, 1.0f), sp.tangent);
  sp.uv[0] = glm::vec2((i + 0.5f) / w, (j + 0.5f) / h);
  return sp;
}

// The decode of `in` must be refused with a message that contains `says`.
inline void expect_refused(const MaterialImages& in, const std::string& says, const std::string& why) {
  try {
    decode_material_texels(in);
    ADD_FAILURE() << why << " was decoded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << why << ": " << e.what();
  }
}

}  // namespace svbrdf::texel_decode
