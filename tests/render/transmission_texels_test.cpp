// KHR_materials_transmission into the level-0 texels (textures/material_loader.h, MaterialTexels::
// transmission_at): the decoded transmission against the extension's text transcribed here in double,
// and against what the renderer shades (render/surface.cpp, shading_params, through SurfaceBsdf) at
// each texel's centre; material_images reads the extension only where it has a factor and names its
// texture by its glTF path, which a refusal repeats.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "appearance/gltf_surface_bsdf.h"
#include "texel_decode.h"

namespace svbrdf {
namespace {

using texel_decode::expect_refused;

// The transmission texture's texels, row by row (RGBA): R from 0 to past 1 (a float image may hold
// more), G and B unlike R so that a read of the wrong channel shows, and mid-range values whose sRGB
// decode differs from them.
constexpr int kW = 3, kH = 2;
constexpr float kRgba[kH][kW][4] = {{{0.0f, 0.9f, 0.3f, 1.0f}, {0.25f, 0.6f, 0.1f, 0.5f}, {0.5f, 0.05f, 0.95f, 1.0f}},
                                    {{0.8f, 0.2f, 0.4f, 0.0f}, {1.0f, 0.0f, 0.7f, 1.0f}, {1.6f, 0.3f, 0.2f, 1.0f}}};
constexpr float kFactor = 0.7f;

Image transmission_image() {
  Image im(kW, kH, 4);
  for (int j = 0; j < kH; ++j)
    for (int i = 0; i < kW; ++i)
      for (int c = 0; c < 4; ++c) im.at(i, j, c) = kRgba[j][i][c];
  return im;
}

// The extension's reading in double ("transmissionTexture": "The percentage of light that is
// transmitted through the surface of the material. Stored in channel R", multiplied by
// transmissionFactor; a percentage, so in [0, 1]). The texture is data, not colour: no sRGB decode.
double khr_transmission(double factor, double r) { return std::clamp(factor * r, 0.0, 1.0); }

TEST(TransmissionTexels, DecodedAsTheExtensionReadsThem) {
  const Image tex = transmission_image();
  MaterialImages in;
  in.transmission = &tex, in.transmission_factor = kFactor;
  const MaterialTexels m = decode_material_texels(in);
  ASSERT_TRUE(m.has_transmission());
  ASSERT_EQ(m.width, kW);
  ASSERT_EQ(m.height, kH);
  ASSERT_EQ(m.transmission.size(), m.size());
  for (int j = 0; j < kH; ++j)
    for (int i = 0; i < kW; ++i)
      EXPECT_NEAR(m.transmission_at(m.index(i, j)), khr_transmission(kFactor, kRgba[j][i][0]), 1e-6)
          << "texel " << i << ", " << j;
  // The texel whose R is past 1 reaches 1 (0.7 · 1.6), not the factor.
  EXPECT_FLOAT_EQ(m.transmission_at(m.index(2, 1)), 1.0f);

  // Without the texture: the factor, per material, no texel array.
  MaterialImages plain;
  plain.transmission_factor = 0.45f;
  const MaterialTexels p = decode_material_texels(plain);
  EXPECT_TRUE(p.has_transmission());
  EXPECT_TRUE(p.transmission.empty());
  EXPECT_FLOAT_EQ(p.transmission_at(0), 0.45f);

  // Factor 0 transmits nothing: the texture is not read, and not part of the texel grid.
  const Image other_size(kW + 1, kH, 4);
  in.transmission_factor = 0.0f, in.transmission = &other_size;
  const MaterialTexels none = decode_material_texels(in);
  EXPECT_FALSE(none.has_transmission());
  EXPECT_TRUE(none.transmission.empty());
  EXPECT_EQ(none.width, 1);
  EXPECT_EQ(none.transmission_at(0), 0.0f);
}

TEST(TransmissionTexels, FactorsOutsideTheExtensionsRangeAreRefused) {
  for (const float factor : {1.5f, -0.25f, NAN}) {
    MaterialImages in;
    in.transmission_factor = factor;
    expect_refused(in, "transmission factor", "factor " + std::to_string(factor));
  }
}

// What SurfaceBsdf makes of a transmission, the rest of the material held fixed: its BSDF value for a
// view above and light from below and from above, and the impulses a view receives, on a thin wall
// (ShadingParams' default) and over a volume. Each is affine in the (clamped) transmission.
std::vector<Rgb> bsdf_response(ShadingParams sh) {
  const glm::vec3 wo = glm::normalize(glm::vec3(-0.2f, 0.1f, 0.95f));
  std::vector<Rgb> out;
  for (const bool thin : {true, false}) {
    sh.thin_walled = thin;
    const SurfaceBsdf bsdf(sh);
    for (const glm::vec3& wi : {glm::vec3(0.3f, 0.1f, -0.9f), glm::vec3(0.2f, -0.3f, 0.9f)})
      out.push_back(bsdf.eval(glm::normalize(wi), wo));
    const Impulses im = bsdf.impulses_in(wo);
    for (int k = 0; k < im.count; ++k) out.push_back(im.items[static_cast<std::size_t>(k)].magnitude);
  }
  return out;
}

// The decode against the renderer: shading_params at each texel's centre (the level0 lookup reads that
// texel), and the BSDF the renderer makes of it, which clamps the transmission. The images reach the
// decode as the MIP builds take them (TextureSet::image, whose `color` picks the sRGB-decoded copy).
TEST(TransmissionTexels, DecodedAsTheRendererShadesThem) {
  Scene s = texel_decode::one_image_scene(transmission_image());
  MaterialDesc textured;
  textured.metallic = 0.0f;
  textured.transmission = kFactor;
  textured.transmission_texture.texture = 0;
  MaterialDesc plain = textured;
  plain.transmission = 0.35f;
  plain.transmission_texture = TextureRef{};
  // A third material shows the same image as colour, so TextureSet holds a linearized copy of it too,
  // which the transmission must not read.
  MaterialDesc shares;
  shares.base_color_texture.texture = 0;
  s.materials = {textured, plain, shares};
  const TextureSet textures(s);
  for (const std::size_t mi : {0u, 1u}) {
    const MaterialDesc& m = s.materials[mi];
    const MaterialTexels texels = texel_decode::decode_as_built(m, textures);
    ASSERT_TRUE(texels.has_transmission());
    for (int j = 0; j < kH; ++j)
      for (int i = 0; i < kW; ++i) {
        const ShadingParams sh = shading_params(texel_decode::texel_centre(m, i, j, kW, kH), textures);
        const std::size_t k = texels.size() == 1 ? 0 : texels.index(i, j);
        const float got = texels.transmission_at(k);
        const std::string where = "material " + std::to_string(mi) + " texel " + std::to_string(i) + ", " + std::to_string(j);
        EXPECT_GE(got, 0.0f) << where;
        EXPECT_LE(got, 1.0f) << where;
        if (sh.transmission <= 1.0f) {
          EXPECT_NEAR(got, sh.transmission, 1e-6) << where;
        }
        ShadingParams decoded = sh;
        decoded.transmission = got;
        const std::vector<Rgb> want = bsdf_response(sh), have = bsdf_response(decoded);
        ASSERT_EQ(have.size(), want.size()) << where;
        for (std::size_t r = 0; r < want.size(); ++r)
          for (int c = 0; c < 3; ++c) EXPECT_NEAR(have[r][c], want[r][c], 1e-6) << where << " response " << r << "." << c;
      }
  }
}

// material_images names the texture by its glTF path (a refusal repeats it), and reads the extension
// only where it has a factor.
TEST(TransmissionTexels, TheTextureIsNamedByItsGltfPath) {
  const Image base(2, 2, 4), wider(3, 2, 4);
  MaterialDesc d;
  d.where = "materials[2]";
  d.base_color_texture.texture = 0;
  d.transmission = 0.5f;
  d.transmission_texture.texture = 1;
  const auto image_of = [&](const TextureRef& r, bool) { return SlotImage{r.texture == 0 ? &base : &wider, false}; };
  const MaterialImages named = material_images(d, image_of, "scene.gltf: ");
  EXPECT_EQ(named.transmission, &wider);
  EXPECT_FLOAT_EQ(named.transmission_factor, 0.5f);
  expect_refused(named, "scene.gltf: materials[2].extensions.KHR_materials_transmission.transmissionTexture",
                 "textures of different sizes");
  d.transmission = 0.0f;
  const MaterialImages opaque = material_images(d, image_of, "scene.gltf: ");
  EXPECT_EQ(opaque.transmission, nullptr);
  EXPECT_FALSE(decode_material_texels(opaque).has_transmission());
}

}  // namespace
}  // namespace svbrdf
