// KHR_materials_anisotropy into the level-0 texels (textures/material_loader.h, MaterialTexels'
// anisotropy layer): the decoded strength and direction against the extension's text transcribed here
// in double, and against what the renderer shades (render/surface.cpp, shading_params) at each texel's
// centre; material_images reads the extension only where it has a strength and names its texture by
// its glTF path, which a refusal repeats.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "texel_decode.h"

namespace svbrdf {
namespace {

using texel_decode::expect_refused;

// The anisotropy texture's texels, row by row (RGB; A unused): directions all round, one RG of
// (0.5, 0.5) (no direction), and strengths from 0 to 1.
constexpr int kW = 3, kH = 2;
constexpr float kRgb[kH][kW][3] = {{{1.0f, 0.5f, 1.0f}, {0.2f, 0.7f, 0.5f}, {0.5f, 0.5f, 0.25f}},
                                   {{0.1f, 0.1f, 0.0f}, {0.75f, 0.3f, 0.8f}, {0.5f, 1.0f, 0.6f}}};
constexpr float kStrength = 0.8f, kRotation = 0.7f;

Image anisotropy_image() {
  Image im(kW, kH, 4);
  for (int j = 0; j < kH; ++j)
    for (int i = 0; i < kW; ++i) {
      for (int c = 0; c < 3; ++c) im.at(i, j, c) = kRgb[j][i][c];
      im.at(i, j, 3) = 1.0f;
    }
  return im;
}

// The extension's reading in double ("anisotropyTexture"): strength = anisotropyStrength · B; the
// direction RG mapped to [−1, 1], normalized, then turned counter-clockwise by anisotropyRotation
// (its GLSL: mat2(c, s, −s, c) · direction). RG = (0.5, 0.5) gives no direction; the renderer then
// takes the tangent's, (1, 0), before the turn.
struct Expected {
  double strength;
  glm::dvec2 direction;
};
Expected khr_anisotropy(double strength, double rotation, const float rgb[3]) {
  glm::dvec2 d(2.0 * rgb[0] - 1.0, 2.0 * rgb[1] - 1.0);
  d = glm::length(d) > 0.0 ? glm::normalize(d) : glm::dvec2(1.0, 0.0);
  const double c = std::cos(rotation), s = std::sin(rotation);
  return {strength * rgb[2], {c * d.x - s * d.y, s * d.x + c * d.y}};
}

void expect_layer(const AnisotropyLayer& got, const Expected& want, const std::string& where) {
  EXPECT_NEAR(got.strength, want.strength, 1e-6) << where;
  EXPECT_NEAR(got.direction.x, want.direction.x, 1e-6) << where;
  EXPECT_NEAR(got.direction.y, want.direction.y, 1e-6) << where;
}

TEST(AnisotropyTexels, DecodedAsTheExtensionReadsThem) {
  const Image tex = anisotropy_image();
  MaterialImages in;
  in.anisotropy = &tex, in.anisotropy_strength = kStrength, in.anisotropy_rotation = kRotation;
  const MaterialTexels m = decode_material_texels(in);
  ASSERT_TRUE(m.has_anisotropy());
  ASSERT_EQ(m.width, kW);
  ASSERT_EQ(m.height, kH);
  ASSERT_EQ(m.anisotropy.size(), m.size());
  ASSERT_EQ(m.anisotropy_direction.size(), m.size());
  for (int j = 0; j < kH; ++j)
    for (int i = 0; i < kW; ++i)
      expect_layer(m.anisotropy_layer(m.index(i, j)), khr_anisotropy(kStrength, kRotation, kRgb[j][i]),
                   "texel " + std::to_string(i) + ", " + std::to_string(j));
  // The texel pointing along the tangent (RG = (1, 0.5)) points along the rotation.
  EXPECT_NEAR(m.anisotropy_layer(0).direction.x, std::cos(kRotation), 1e-6);
  EXPECT_NEAR(m.anisotropy_layer(0).direction.y, std::sin(kRotation), 1e-6);

  // Without the texture: the strength and the rotation's direction, per material, no texel arrays.
  MaterialImages plain;
  plain.anisotropy_strength = 0.6f, plain.anisotropy_rotation = -2.0f;
  const MaterialTexels p = decode_material_texels(plain);
  EXPECT_TRUE(p.anisotropy.empty());
  EXPECT_TRUE(p.anisotropy_direction.empty());
  const float along[3] = {1.0f, 0.5f, 1.0f};
  expect_layer(p.anisotropy_layer(0), khr_anisotropy(0.6, -2.0, along), "factor only");

  // Strength 0 is isotropic: the texture is not read, and not part of the texel grid.
  const Image other_size(kW + 1, kH, 4);
  in.anisotropy_strength = 0.0f, in.anisotropy = &other_size;
  const MaterialTexels none = decode_material_texels(in);
  EXPECT_FALSE(none.has_anisotropy());
  EXPECT_TRUE(none.anisotropy.empty());
  EXPECT_EQ(none.width, 1);
}

TEST(AnisotropyTexels, FactorsOutsideTheExtensionsRangeAreRefused) {
  for (const float strength : {1.5f, -0.25f, NAN}) {
    MaterialImages in;
    in.anisotropy_strength = strength;
    expect_refused(in, "anisotropy strength", "strength " + std::to_string(strength));
  }
  MaterialImages in;
  in.anisotropy_strength = 0.5f, in.anisotropy_rotation = INFINITY;
  expect_refused(in, "anisotropy rotation", "an infinite rotation");
}

// The decode against the renderer: shading_params at each texel's centre (the level0 lookup reads that
// texel) on a surface whose shading frame is the tangent frame, where the renderer's direction is the
// tangent-space one. The images reach the decode as the MIP builds take them (TextureSet::image).
TEST(AnisotropyTexels, DecodedAsTheRendererShadesThem) {
  Scene s = texel_decode::one_image_scene(anisotropy_image());
  MaterialDesc textured;
  textured.anisotropy_strength = kStrength, textured.anisotropy_rotation = kRotation;
  textured.anisotropy_texture.texture = 0;
  MaterialDesc plain;
  plain.anisotropy_strength = 0.35f, plain.anisotropy_rotation = 2.5f;
  s.materials = {textured, plain};
  const TextureSet textures(s);
  for (const MaterialDesc& m : s.materials) {
    const MaterialTexels texels = texel_decode::decode_as_built(m, textures);
    ASSERT_TRUE(texels.has_anisotropy());
    for (int j = 0; j < kH; ++j)
      for (int i = 0; i < kW; ++i) {
        const ShadingParams sh = shading_params(texel_decode::texel_centre(m, i, j, kW, kH), textures);
        const std::size_t k = texels.size() == 1 ? 0 : texels.index(i, j);
        const AnisotropyLayer a = texels.anisotropy_layer(k);
        const std::string where = m.where + " texel " + std::to_string(i) + ", " + std::to_string(j);
        EXPECT_NEAR(a.strength, sh.anisotropy, 1e-6) << where;
        EXPECT_NEAR(a.direction.x, sh.anisotropy_direction.x, 1e-6) << where;
        EXPECT_NEAR(a.direction.y, sh.anisotropy_direction.y, 1e-6) << where;
      }
  }
}

// material_images names the texture by its glTF path (a refusal repeats it), and reads the extension
// only where it has a strength.
TEST(AnisotropyTexels, TheTextureIsNamedByItsGltfPath) {
  const Image base(2, 2, 4), wider(3, 2, 4);
  MaterialDesc d;
  d.where = "materials[2]";
  d.base_color_texture.texture = 0;
  d.anisotropy_strength = 0.5f;
  d.anisotropy_texture.texture = 1;
  const auto image_of = [&](const TextureRef& r, bool) { return SlotImage{r.texture == 0 ? &base : &wider, false}; };
  const MaterialImages named = material_images(d, image_of, "scene.gltf: ");
  EXPECT_EQ(named.anisotropy, &wider);
  EXPECT_FLOAT_EQ(named.anisotropy_strength, 0.5f);
  expect_refused(named, "scene.gltf: materials[2].extensions.KHR_materials_anisotropy.anisotropyTexture",
                 "textures of different sizes");
  d.anisotropy_strength = 0.0f;
  const MaterialImages isotropic = material_images(d, image_of, "scene.gltf: ");
  EXPECT_EQ(isotropic.anisotropy, nullptr);
  EXPECT_FALSE(decode_material_texels(isotropic).has_anisotropy());
}

}  // namespace
}  // namespace svbrdf
