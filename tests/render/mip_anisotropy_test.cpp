// The anisotropy (KHR_materials_anisotropy) through the MIP filters in the renderer: the textured quad
// of mip_quad.h (A B / C D) under an anisotropy whose strength and direction come from its texture and
// differ in every texel of a level-3 texel, seen at level 3 (each pixel covers 4 copies of a coarse
// texel's 64 texels) under a directional light, black sky. The expectation is the closed form of
// ../shared/spec/brdf-mip.md: E·wi.z times the mean over the four texels of f_eff, each texel's
// evaluated by the renderer's surface BSDF (SurfaceBsdf, the extension's anisotropic GGX) — never by
// the mip module. level0 at many samples (the supersampled ground truth) converges to the same mean.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <cstdio>
#include <string>

#include "appearance/gltf_surface_bsdf.h"
#include "mip_quad.h"
#include "tests/common/test_paths.h"
#include "gltf/scene_reader.h"
#include "render/material_mips.h"

namespace svbrdf {
namespace {

using namespace mip_quad;

// The anisotropy of texel (i, j): within each 8 × 8 block (a level-3 texel) every texel has its own
// strength (anisotropyTexture.b, 0.3–0.9) and direction (its RG, at 22.5° steps along a row and 5° down
// a column), so a coarse texel's 64 stretched lobes must be merged to its 4 slots; the base parameters
// are A B / C D's.
float strength(int i, int j) { return 0.3f + 0.6f * float((i + 3 * j) % 8) / 7.0f; }
glm::vec2 direction(int i, int j) {
  const float a = glm::radians(22.5f * float(i % 8) + 5.0f * float(j % 8));
  return {std::cos(a), std::sin(a)};
}

// The quad with flat normals (the tangent frame is the shading frame) and the anisotropy texture.
Scene anisotropy_quad() {
  Scene s = periodic_quad();
  const int size = 256;
  Image a(size, size, 4);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const glm::vec2 d = direction(i, j);
      a.at(i, j, 0) = 0.5f * d.x + 0.5f, a.at(i, j, 1) = 0.5f * d.y + 0.5f;
      a.at(i, j, 2) = strength(i, j), a.at(i, j, 3) = 1.0f;
    }
  MaterialDesc& m = s.materials[0];
  m.normal_texture = TextureRef{};
  m.anisotropy_strength = 1.0f;
  m.anisotropy_texture.texture = test::add_image_texture(s, std::move(a));
  return s;
}

// f_eff of texel (i, j) under its anisotropy, about the geometric normal: SurfaceBsdf.
glm::dvec3 anisotropic_f_eff(int i, int j, const glm::vec3& wi, const glm::vec3& wo) {
  if (wi.z <= 0 || wo.z <= 0) return glm::dvec3(0);
  const TexelSpec& t = pattern_texel(i, j);
  ShadingParams p;
  p.base_color = linear(t.srgb), p.metallic = t.metallic, p.roughness = t.roughness;
  p.anisotropy = strength(i, j), p.anisotropy_direction = direction(i, j);
  return glm::dvec3(SurfaceBsdf(p).eval(wi, wo));
}

// The exact coarse texel of level 3 (every block is the same): the mean of its 64 texels' f_eff.
glm::dvec3 mean_f_eff(const glm::vec3& wi, const glm::vec3& wo) {
  return block_mean([&](int i, int j) { return anisotropic_f_eff(i, j, wi, wo); });
}

// Before the stretched lobes the renderer warned that such a material is "shaded with level0 lookups".
TEST(MipAnisotropy, AnAnisotropicMaterialTakesPartInTheMipFilters) {
  Prepared p(anisotropy_quad());
  EXPECT_NE(p.mips->find(0), nullptr);
  EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
}

// A glTF material with every layer the BRDF pyramid carries (KHR_materials_specular, _ior, _clearcoat,
// _sheen, _anisotropy; the fuzz corpus's layered material) is filtered, not left at level 0, and its
// coarse texels hold stretched lobes.
TEST(MipAnisotropy, AMaterialWithEveryLayerTakesPartInTheMipFilters) {
  const std::filesystem::path file =
      std::filesystem::path(SVBRDF_SOURCE_DIR) / "fuzz/corpus/gltf/layered-specular-clearcoat-sheen-anisotropy.gltf";
  Prepared p(load_gltf(file));
  ASSERT_EQ(p.scene.materials.size(), 1u);
  const MaterialDesc& m = p.scene.materials[0];
  ASSERT_GT(m.anisotropy_strength, 0.0f);
  ASSERT_GT(m.clearcoat, 0.0f);
  ASSERT_GT(max_channel(m.sheen_color), 0.0f);
  ASSERT_NE(m.ior, 1.5f);
  ASSERT_NE(p.mips->find(0), nullptr);
  EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty()) << p.mips->warnings(TextureFilter::brdf).front();
  p.mips->prepare(TextureFilter::brdf);
  MipTexture::Scratch scratch;
  const MipTexture& t = p.mips->find(0)->texture();
  const MipTexture::Choice c = t.choose(TextureFilter::brdf, Footprint{{0.5f, 0.5f}, {0.25f, 0}, {0, 0.25f}}, Rgb(1.0f), 0.5f);
  ASSERT_GE(c.level, 1);
  bool stretched = false;
  for (const Lobe& l : t.lobes(c, scratch)) stretched = stretched || l.stretch > 1.0f;
  EXPECT_TRUE(stretched);
}

// brdf's render at level 3 against the closed form, head-on and from 65° at two azimuths: the 64
// texels' lobes are stretched along 64 directions, which a coarse texel holds as at most 4 merged
// lobes and their stretches (mip/slope_stretch.h). Lobes stretched across each other merge into a
// roughness band about their mean stretch, whose radial profile lacks the shoulder of the azimuthal
// mean of a stretched GGX: measured (printed) −15 / −21 / −15 % head-on, −16 / −19 / −18 % and
// −2 / −6 / −6 % from 65° (RGB; the light's half vector 17.5–30° off the normal); the bar is what that
// reaches, rounded up, not the 6 % of the other layers (docs/mip-algorithm.md, "Stretched lobes").
TEST(MipAnisotropy, BrdfFollowsTheMeanOfTheCoveredTexels) {
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(65, 200), tilted(65, 110)}) {
    const std::string what = "view " + std::to_string(wo.x) + "," + std::to_string(wo.y) + "," + std::to_string(wo.z);
    const glm::dvec3 want = kE0 * double(kWi.z) * mean_f_eff(kWi, wo);
    const glm::dvec3 got = image_mean(render_quad(anisotropy_quad(), TextureFilter::brdf, 16, wo).radiance());
    std::printf("%s: brdf %+.4f %+.4f %+.4f relative to the mean (RGB)\n", what.c_str(), got.r / want.r - 1,
                got.g / want.g - 1, got.b / want.b - 1);
    expect_rgb_near(got, want, 0.25, "brdf, " + what);
  }
}

// The ground truth: level0 at many samples converges to the same closed form (1 %; 262144 samples of
// 64 texel values).
TEST(MipAnisotropy, Level0ConvergesToTheSameMean) {
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(65, 200)}) {
    const Image im = render_quad(anisotropy_quad(), TextureFilter::level0, 256, wo).radiance();
    expect_rgb_near(image_mean(im), kE0 * double(kWi.z) * mean_f_eff(kWi, wo), 1e-2,
                    "level0, view z " + std::to_string(wo.z));
  }
}

// At distance 0 (a pixel's footprint a sixteenth of a texel) brdf reads level 0, and its image converges
// to level0's (1 %).
TEST(MipAnisotropy, BrdfAtDistanceZeroConvergesToLevel0) {
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(65, 200)}) {
    const glm::dvec3 brdf = image_mean(render_quad(anisotropy_quad(), TextureFilter::brdf, 64, wo, 1.0f / 128).radiance());
    const glm::dvec3 level0 = image_mean(render_quad(anisotropy_quad(), TextureFilter::level0, 64, wo, 1.0f / 128).radiance());
    expect_rgb_near(brdf, level0, 1e-2, "view z " + std::to_string(wo.z));
  }
}

}  // namespace
}  // namespace svbrdf
