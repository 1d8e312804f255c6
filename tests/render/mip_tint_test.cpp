// COLOR_0 and a base colour texture mapped apart from the rest, as tints of the BRDF texels
// (mip/lobe.h tinted, render/material_mips.h), checked against closed forms on the textured quad of
// mip_quad.h: every pixel E · wi.z · F, F the mean f_eff of the covered texels with their tinted base
// colours (glTF 2.0 §3.9.2: COLOR_0 multiplies the base colour).
#include <gtest/gtest.h>

#include "mip_quad.h"

namespace svbrdf {
namespace {

using namespace mip_quad;

// Under a COLOR_0 tint, `brdf` is still the mean f_eff of the covered texels, now of their tinted
// base colors (glTF 2.0 §3.9.2: COLOR_0 multiplies the base color), metals (B, D) and dielectrics
// (A, C) alike: the material's pyramid is built tintable because its primitive is tinted.
TEST(MipFilters, BrdfUnderATintIsTheMeanOfTheTintedTexels) {
  const glm::vec3 tint(0.9f, 0.35f, 0.6f);
  Scene s = periodic_quad();
  s.meshes[0].primitives[0].colors.assign(4, glm::vec4(tint, 1.0f));
  auto tinted = [&](TexelSpec t) {
    const Rgb c = linear(t.srgb) * tint;
    return f_eff(c, t.metallic, t.roughness, stored_normal(t.normal), kWi, glm::vec3(0, 0, 1));
  };
  const glm::dvec3 want = kE0 * double(kWi.z) * (tinted(kA) + tinted(kB) + tinted(kC) + tinted(kD)) / 4.0;
  const Image im = render_quad(s, TextureFilter::brdf, 16).radiance();
  expect_rgb_near(image_mean(im), want, 5e-3, "brdf under a tint");
  expect_rgb_near(pixel(im, 7, 20), want, 5e-3, "brdf under a tint, one pixel");
}

// A base colour texture looked up otherwise than the other textures — through another
// KHR_texture_transform, another TEXCOORD set, another wrap mode — is held apart as a tint of the
// grid (render/material_mips.h): the material takes part with no warning, and `brdf` is the mean f_eff
// of the covered texels with the base colour texture's colour (uniform here, so the tint is exact).
TEST(MipFilters, BaseColorOnItsOwnMappingTintsTheGrid) {
  const glm::vec3 srgb(0.7f, 0.3f, 0.5f);
  glm::dvec3 want(0);
  for (const TexelSpec& t : {kA, kB, kC, kD})
    want += f_eff(linear(srgb), t.metallic, t.roughness, stored_normal(t.normal), kWi, glm::vec3(0, 0, 1)) / 4.0;
  want *= kE0 * double(kWi.z);
  for (const std::string variant : {"transform", "uv set", "wrap"}) {
    Scene s = periodic_quad();
    Image base(4, 4, 3);
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)
        for (int c = 0; c < 3; ++c) base.at(i, j, c) = srgb[c];
    s.images[0].pixels = base;
    if (variant == "transform") s.materials[0].base_color_texture.transform = TextureTransform::make({0.5f, 0}, 0.3f, {3, 3});
    if (variant == "uv set") {
      s.materials[0].base_color_texture.tex_coord = 1;
      s.meshes[0].primitives[0].texcoords[1] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    }
    if (variant == "wrap") s.textures[0].sampler.wrap_t = WrapMode::mirrored_repeat;
    {
      Prepared p(s);
      ASSERT_NE(p.mips->find(0), nullptr) << variant;
      EXPECT_TRUE(p.mips->find(0)->separate_base_color()) << variant;
      EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty()) << variant;
    }
    const Image im = render_quad(s, TextureFilter::brdf, 16).radiance();
    expect_rgb_near(image_mean(im), want, 5e-3, "brdf, base colour by " + variant);
    expect_rgb_near(pixel(im, 7, 20), want, 5e-3, "brdf, base colour by " + variant + ", one pixel");
  }
  // The tint is the base colour filtered over the footprint: a 64² checker of two colours, scaled 8×,
  // spans 16 of its texels per pixel and 4 per sample (the filters' footprint is a sample's, 1/√16 of
  // the pixel's), where the coarse levels hold its mean: every pixel sees its linear mean (the BRDF is
  // linear in the base colour).
  const glm::vec3 srgb2(0.2f, 0.9f, 0.6f);
  const Rgb mean_color = 0.5f * (linear(srgb) + linear(srgb2));
  glm::dvec3 want2(0);
  for (const TexelSpec& t : {kA, kB, kC, kD})
    want2 += f_eff(mean_color, t.metallic, t.roughness, stored_normal(t.normal), kWi, glm::vec3(0, 0, 1)) / 4.0;
  want2 *= kE0 * double(kWi.z);
  Scene s = periodic_quad();
  Image checker(64, 64, 3);
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i)
      for (int c = 0; c < 3; ++c) checker.at(i, j, c) = ((i + j) % 2 ? srgb : srgb2)[c];
  s.images[0].pixels = checker;
  s.materials[0].base_color_texture.transform = TextureTransform::make({0, 0}, 0, {8.0f, 8.0f});
  const Image im = render_quad(s, TextureFilter::brdf, 16).radiance();
  expect_rgb_near(image_mean(im), want2, 5e-3, "brdf, a filtered base colour");
  expect_rgb_near(pixel(im, 7, 20), want2, 5e-3, "brdf, a filtered base colour, one pixel");
}

// COLOR_0 tints the base color: exact for level0 and param; on a texture not built for tints (no
// primitive of the material has a COLOR_0 that is not white) brdf answers a tinted hit as level0.
TEST(MipFilters, VertexColorTint) {
  Prepared p(periodic_quad(16));
  p.mips->prepare(TextureFilter::brdf);
  p.mips->prepare(TextureFilter::param);
  const MaterialMip* mip = p.mips->find(0);
  ASSERT_NE(mip, nullptr);
  const Rgb tint(0.5f, 1.0f, 0.25f);
  const Footprint f{{0.5f / 16, 0.5f / 16}, {0.2f, 0}, {0, 0.2f}};
  MipTexture::Scratch s0, s1;
  const Lobe l0 = mip->texture().lobes(TextureFilter::level0, f, tint, 0.3f, s0)[0];
  EXPECT_TRUE(same_lobes(mip->texture().lobes(TextureFilter::brdf, f, tint, 0.3f, s1), {&l0, 1}));
  // Texel A is a dielectric: ρ = c·tint, F0 = 0.04.
  const Rgb c = linear(kA.srgb);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(l0.diffuse[k], c[k] * tint[k], 1e-6f);
  const Lobe pl = mip->texture().lobes(TextureFilter::param, f, tint, 0.0f, s0)[0];
  const Lobe pw = mip->texture().lobes(TextureFilter::param, f, Rgb(1), 0.0f, s1)[0];
  EXPECT_NEAR(pl.diffuse.x, 0.5f * pw.diffuse.x, 1e-6f);
  EXPECT_NEAR(pl.diffuse.z, 0.25f * pw.diffuse.z, 1e-6f);
}

}  // namespace
}  // namespace svbrdf
