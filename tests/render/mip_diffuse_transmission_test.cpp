// A diffuse transmission (KHR_materials_diffuse_transmission) through the MIP filters in the renderer: the
// textured quad of mip_quad.h (A B / C D) with flat normals and a diffuse transmission whose share
// (diffuseTransmissionTexture.a) and colour (diffuseTransmissionColorTexture, sRGB) differ across a
// level-3 texel, seen at level 3 (each pixel covers 4 copies of a coarse texel's 64 texels) under a sun
// behind the quad, black sky. The expectation is the closed form of ../shared/spec/brdf-mip.md: E·|wi.z|
// times the mean over the texels of f_eff, each texel's evaluated by the renderer's surface BSDF
// (SurfaceBsdf, the extension's Lambertian BTDF) — never by the mip module.
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <utility>

#include "appearance/gltf_surface_bsdf.h"
#include "mip_quad.h"
#include "render/material_mips.h"

namespace svbrdf {
namespace {

using namespace mip_quad;

// The share of texel (i, j): 0, 0.3, 0.6 and 0.95 in turn, a step every two texels along a row and every
// texel down a column, so each of A B C D takes all four in a level-3 texel; the colour (sRGB-encoded)
// one of four in another pattern, so the lobes a coarse texel merges differ in τd's colour too.
float share(int i, int j) {
  constexpr float kSteps[4] = {0.0f, 0.3f, 0.6f, 0.95f};
  return kSteps[(i / 2 + j) % 4];
}
const glm::vec3 kColorSrgb[4] = {{0.95f, 0.8f, 0.3f}, {0.2f, 0.9f, 0.6f}, {0.7f, 0.3f, 0.95f}, {1.0f, 1.0f, 1.0f}};
const glm::vec3& color_srgb(int i, int j) { return kColorSrgb[(i + j / 2) % 4]; }

// The quad with flat normals (the tangent frame is the shading frame) and the two textures.
Scene diffusely_transmitting_quad() {
  Scene s = periodic_quad();
  const int size = 256;
  Image d(size, size, 4), c(size, size, 3);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      d.at(i, j, 0) = d.at(i, j, 1) = d.at(i, j, 2) = 1.0f, d.at(i, j, 3) = share(i, j);
      for (int k = 0; k < 3; ++k) c.at(i, j, k) = color_srgb(i, j)[k];
    }
  MaterialDesc& m = s.materials[0];
  m.normal_texture = TextureRef{};
  m.diffuse_transmission = 1.0f;
  m.diffuse_transmission_texture.texture = test::add_image_texture(s, std::move(d));
  m.diffuse_transmission_color_texture.texture = test::add_image_texture(s, std::move(c));
  return s;
}

// f_eff of texel (i, j) about the geometric normal (flat): SurfaceBsdf's.
glm::dvec3 texel_f_eff(int i, int j, const glm::vec3& wi, const glm::vec3& wo) {
  const TexelSpec& t = pattern_texel(i, j);
  ShadingParams p;
  p.base_color = linear(t.srgb), p.metallic = t.metallic, p.roughness = t.roughness;
  p.diffuse_transmission = share(i, j);
  p.diffuse_transmission_color = linear(color_srgb(i, j));
  return glm::dvec3(SurfaceBsdf(p).eval(wi, wo));
}

const glm::vec3 kBehind(kWi.x, kWi.y, -kWi.z);  // toward a sun behind the quad

Film render(TextureFilter filter, int spp, const glm::vec3& view, float footprint_scale = 1.0f) {
  Scene s = diffusely_transmitting_quad();
  s.lights.push_back(sun(kBehind));
  return render_quad(std::move(s), filter, spp, view, footprint_scale);
}

// Before the lobes carried it the renderer warned that such a material is "shaded with level0 lookups".
TEST(MipDiffuseTransmission, TakesPartInTheMipFilters) {
  Prepared p(diffusely_transmitting_quad());
  EXPECT_NE(p.mips->find(0), nullptr);
  EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
}

// Lit from behind, head-on and from 65°: brdf at level 3 (the 64 texels' lobes merged to at most 4) and
// level0 at many samples (the supersampled ground truth) both gather the light that crosses the surface,
// and each image's mean is the closed form within 4 of its standard errors and, for brdf, the file's
// rounding of the lobes' weight and τd (2^-11 relative each, 4·10⁻³ allowed as
// DiffuseTransmissionPyramid.Level1IsTheExactMean allows it). A Lambertian BTDF's union is exact under a
// merge on flat normals (its shape is fixed and the merge keeps its flux, mip/diffuse_transmission.h),
// so no other allowance is made. Were the light behind the quad not gathered for lobes (the integrator's
// lit_from_behind), brdf's image would be black.
TEST(MipDiffuseTransmission, BrdfAtLevel3GathersTheLightFromBehindAsLevel0Does) {
  for (const glm::vec3& view : {glm::vec3(0, 0, 1), tilted(65, 200)}) {
    const std::string what = "view z " + std::to_string(view.z);
    const glm::dvec3 want = kE0 * double(-kBehind.z) *
                            block_mean([&](int i, int j) { return texel_f_eff(i, j, kBehind, view); });
    ASSERT_GT(want.r, 0.0);
    const Image brdf = render(TextureFilter::brdf, 16, view).radiance();
    const Image level0 = render(TextureFilter::level0, 256, view).radiance();
    for (const auto& [name, im] : {std::pair<const char*, const Image*>{"brdf", &brdf}, {"level0", &level0}}) {
      const glm::dvec3 got = image_mean(*im), se = standard_error(*im);
      std::printf("%s, %s: %+.4f %+.4f %+.4f relative to the mean (RGB), standard error %.4f %.4f %.4f\n", name,
                  what.c_str(), got.r / want.r - 1, got.g / want.g - 1, got.b / want.b - 1, se.r / want.r,
                  se.g / want.g, se.b / want.b);
    }
    expect_within(image_mean(brdf), want, standard_error(brdf) + 1e-3 * want, "brdf, " + what);
    expect_within(image_mean(level0), want, standard_error(level0), "level0, " + what);
  }
}

}  // namespace
}  // namespace svbrdf
