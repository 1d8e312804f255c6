// The sheen (KHR_materials_sheen) through the MIP filters in the renderer: the textured quad of
// mip_quad.h (A B / C D) under a sheen whose colour and roughness come from textures, seen at level 3
// (each pixel covers 16 copies of the four texels) under a directional light, black sky. The
// expectation is the closed form of ../shared/spec/brdf-mip.md: E·wi.z times the mean over the four
// texels of f_eff, each texel's evaluated by the renderer's surface BSDF (SurfaceBsdf, the extension's
// albedo scaling) in a frame about its normal — never by the mip module. level0 at many samples (the
// supersampled ground truth, shaded by SurfaceBsdf) converges to the same mean.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "appearance/gltf_surface_bsdf.h"
#include "mip_quad.h"
#include "render/material_mips.h"

namespace svbrdf {
namespace {

using namespace mip_quad;

// The sheen of A B C D: colour (sheenColorTexture.rgb, sRGB-encoded) and perceptual roughness
// (sheenRoughnessTexture.a); D has none.
const glm::vec3 kSheenSrgb[4] = {{1.0f, 0.9f, 0.8f}, {0.3f, 0.6f, 0.9f}, {0.8f, 0.2f, 0.5f}, {0.0f, 0.0f, 0.0f}};
constexpr float kSheenRoughness[4] = {0.3f, 0.8f, 0.5f, 0.6f};

Scene sheen_quad() {
  Scene s = periodic_quad();
  const int size = 256;
  Image color(size, size, 4), rough(size, size, 4);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const int k = (j % 2) * 2 + i % 2;  // A B / C D
      for (int c = 0; c < 3; ++c) color.at(i, j, c) = kSheenSrgb[k][c], rough.at(i, j, c) = 0.0f;
      color.at(i, j, 3) = 1.0f, rough.at(i, j, 3) = kSheenRoughness[k];
    }
  MaterialDesc& m = s.materials[0];
  m.normal_texture = TextureRef{};
  m.sheen_color = Rgb(1.0f);
  m.sheen_color_texture.texture = test::add_image_texture(s, std::move(color));
  m.sheen_roughness = 1.0f;
  m.sheen_roughness_texture.texture = test::add_image_texture(s, std::move(rough));
  return s;
}

// f_eff of one texel under its sheen, about the surface's normal: SurfaceBsdf.
glm::dvec3 sheen_f_eff(const TexelSpec& t, int k, const glm::vec3& wi, const glm::vec3& wo) {
  if (wi.z <= 0 || wo.z <= 0) return glm::dvec3(0);
  ShadingParams p;
  p.base_color = linear(t.srgb), p.metallic = t.metallic, p.roughness = t.roughness;
  p.sheen_color = linear(kSheenSrgb[k]), p.sheen_roughness = kSheenRoughness[k];
  return glm::dvec3(SurfaceBsdf(p).eval(wi, wo));
}

// The exact coarse texel: the mean of the four texels' f_eff.
glm::dvec3 mean_sheen_f_eff(const glm::vec3& wi, const glm::vec3& wo) {
  const TexelSpec texels[4] = {kA, kB, kC, kD};
  glm::dvec3 mean(0);
  for (int k = 0; k < 4; ++k) mean += sheen_f_eff(texels[k], k, wi, wo) / 4.0;
  return mean;
}

// Before the sheen layer the renderer warned that such a material is "shaded with level0 lookups".
TEST(MipSheen, ASheenMaterialTakesPartInTheMipFilters) {
  Prepared p(sheen_quad());
  EXPECT_NE(p.mips->find(0), nullptr);
  EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
}

// brdf's render at level 3 against the closed form, head-on and from 65°: the four texels' sheens
// differ in colour and in roughness (0.3–0.8), which a coarse texel holds as one mean colour and
// roughness and each base lobe's share (sheen_layer.h). Measured (printed): 1.2 / 0.4 / 4.9 % off
// head-on and 1.1 / 2.4 / 3.8 % from 65° (RGB; blue, where the sheens' colours differ most); the bar is
// 6 %.
TEST(MipSheen, BrdfFollowsTheMeanOfTheCoveredTexels) {
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(65, 200)}) {
    const std::string what = "view z " + std::to_string(wo.z);
    const glm::dvec3 want = kE0 * double(kWi.z) * mean_sheen_f_eff(kWi, wo);
    const glm::dvec3 got = image_mean(render_quad(sheen_quad(), TextureFilter::brdf, 16, wo).radiance());
    std::printf("%s: brdf %+.4f %+.4f %+.4f relative to the mean (RGB)\n", what.c_str(), got.r / want.r - 1,
                got.g / want.g - 1, got.b / want.b - 1);
    expect_rgb_near(got, want, 6e-2, "brdf, " + what);
  }
}

// The ground truth: level0 at many samples converges to the same closed form (65536 samples of four
// texel values; 1 %), head-on and from 65°.
TEST(MipSheen, Level0ConvergesToTheSameMean) {
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(65, 200)}) {
    const Image im = render_quad(sheen_quad(), TextureFilter::level0, 64, wo).radiance();
    expect_rgb_near(image_mean(im), kE0 * double(kWi.z) * mean_sheen_f_eff(kWi, wo), 1e-2,
                    "level0, view z " + std::to_string(wo.z));
  }
}

// At distance 0 (a pixel's footprint a sixteenth of a texel) brdf reads level 0, and its image converges
// to level0's (1 %, as above).
TEST(MipSheen, BrdfAtDistanceZeroConvergesToLevel0) {
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(65, 200)}) {
    const glm::dvec3 brdf = image_mean(render_quad(sheen_quad(), TextureFilter::brdf, 64, wo, 1.0f / 128).radiance());
    const glm::dvec3 level0 = image_mean(render_quad(sheen_quad(), TextureFilter::level0, 64, wo, 1.0f / 128).radiance());
    expect_rgb_near(brdf, level0, 1e-2, "view z " + std::to_string(wo.z));
  }
}

}  // namespace
}  // namespace svbrdf
