// The MIP texture filters in the renderer (mip/mip.h through render/material_mips.h),
// checked against closed forms of ../shared/spec/brdf-mip.md: a textured quad seen by an
// orthographic camera under a directional light E from wi, black environment, has pixel value
//   E · wi.z · F(wi, wo),
// F the footprint's filtered BRDF. For a level-L texel F is the mean of its covered texels' f_eff,
//   f_eff,x(wi, wo) = f_x(wi, wo) · max(0, n_x·wi) / wi.z,
// f_x the glTF BRDF (appearance/gltf.h) in a frame about the texel's normal n_x; for `param` it is
// f_eff of one texel with the covered texels' mean parameters. The expectations are computed here
// from the texel values with gltf_eval, never from the renderer or the mip module.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "appearance/frame.h"
#include "appearance/gltf.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/rng.h"
#include "render/material_mips.h"
#include "render/surface.h"
#include "mip_quad.h"
#include "render_test_scenes.h"
#include "textures/color.h"
#include "textures/normal_map.h"

namespace svbrdf {
namespace {

using namespace mip_quad;

// The premise of the tests below: the closed forms of `brdf` and `param` differ, by far more than
// the tolerances, at the pairs the renders look at.
TEST(MipFilters, ClosedFormsDiffer) {
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(50, 180)}) {
    const glm::dvec3 brdf = mean_f_eff({kA, kB, kC, kD}, kWi, wo), param = param_f_eff({kA, kB, kC, kD}, kWi, wo);
    EXPECT_GT(glm::length(brdf - param), 0.1 * glm::length(brdf));
  }
}

// `brdf` on a texture whose level-3 texels all cover A B C D: every pixel is the mean f_eff of the
// four, head-on (isotropic footprint) and from 50° (anisotropic: two probes).
TEST(MipFilters, BrdfIsTheMeanOfTheCoveredTexels) {
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(50, 180)}) {
    const Image im = render_quad(periodic_quad(), TextureFilter::brdf, 16, wo).radiance();
    const glm::dvec3 want = kE0 * double(kWi.z) * mean_f_eff({kA, kB, kC, kD}, kWi, wo);
    // The coarse texels keep the four lobes (their colors rounded to half floats, 5e-4).
    expect_rgb_near(image_mean(im), want, 5e-3, "brdf, view z " + std::to_string(wo.z));
    expect_rgb_near(pixel(im, 7, 20), want, 5e-3, "brdf, one pixel, view z " + std::to_string(wo.z));
  }
}

// `param`: the f_eff of the averaged parameters (mean linear color, metallic, roughness; normal
// the normalized mean) of the same texels.
TEST(MipFilters, ParamIsTheBrdfOfTheMeanParameters) {
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(50, 180)}) {
    const Image im = render_quad(periodic_quad(), TextureFilter::param, 4, wo).radiance();
    const glm::dvec3 want = kE0 * double(kWi.z) * param_f_eff({kA, kB, kC, kD}, kWi, wo);
    expect_rgb_near(image_mean(im), want, 2e-4, "param, view z " + std::to_string(wo.z));
    expect_rgb_near(pixel(im, 20, 3), want, 2e-4, "param, one pixel");
  }
}

// level0 at many samples: each pixel covers 8×8 texels, 16 copies of A B C D, so its mean is the
// same closed form as brdf's (the ground truth brdf converges to).
TEST(MipFilters, Level0ConvergesToTheSameMean) {
  const Image im = render_quad(periodic_quad(), TextureFilter::level0, 64).radiance();
  const glm::dvec3 want = kE0 * double(kWi.z) * mean_f_eff({kA, kB, kC, kD}, kWi, {0, 0, 1});
  // 65536 samples of four texel values: σ/mean ≈ 0.7/256 ≈ 3e-3 at worst; 1 % is three of those.
  expect_rgb_near(image_mean(im), want, 1e-2, "level0");
}

// Stochastic selection: on the checkerboard of level-3 texels P (A B C D) and Q (E), pixel-aligned,
// a pixel's samples spread uniformly over its texel, where the bilinear weights of the texel and
// its neighbours average (1/8, 3/4, 1/8) per axis: a P pixel is 0.625·F_P + 0.375·F_Q in
// expectation (its four diagonal neighbours are P, its four edge neighbours Q), a Q pixel the reverse.
TEST(MipFilters, BrdfSelectsTexelsWithTheFilterWeights) {
  const Image im = render_quad(checker_quad(), TextureFilter::brdf, 64).radiance();
  const glm::vec3 wo(0, 0, 1);
  const glm::dvec3 fp = kE0 * double(kWi.z) * mean_f_eff({kA, kB, kC, kD}, kWi, wo);
  const glm::dvec3 fq = kE0 * double(kWi.z) * f_eff(kE, kWi, wo);
  // The view's left edge is u = 1.5 (texel 384, level-3 texel 48, even), its top v = 1.5.
  glm::dvec3 on_p(0), on_q(0);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x) ((x + y) % 2 ? on_q : on_p) += pixel(im, x, y) / 512.0;
  // Each mean has 32768 samples of two values: σ ≤ 0.5·|F_P − F_Q|/181; 4σ ≈ 0.011·|F_P − F_Q|.
  for (int c = 0; c < 3; ++c) {
    const double tol = 0.011 * std::abs(fp[c] - fq[c]) + 5e-3 * fp[c];
    EXPECT_NEAR(on_p[c], 0.625 * fp[c] + 0.375 * fq[c], tol) << "P pixels, channel " << c;
    EXPECT_NEAR(on_q[c], 0.375 * fp[c] + 0.625 * fq[c], tol) << "Q pixels, channel " << c;
  }
}

// Bit-identical images for any number of threads with the stochastic selection on, and another
// image from another seed.
TEST(MipFilters, BrdfDeterministicAcrossThreadCounts) {
  auto make = [] {
    Rng rng(11, 1);
    const TexelSpec choices[5] = {kA, kB, kC, kD, kE};
    std::vector<int> pick(64 * 64);
    for (int& k : pick) k = int(rng.next_u32() % 5);
    Scene s = textured_quad(64, [&](int i, int j) { return choices[pick[std::size_t(j) * 64 + i]]; });
    // Perspective: footprints vary over the image; a tilted second quad gets secondary rays.
    s.cameras.push_back(test::perspective_camera({1, 2, 6}, {0, 0, 0}, 40.0f));
    test::add_quad(s, 0, glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, 1)) *
                             glm::rotate(glm::dmat4(1.0), glm::radians(80.0), glm::dvec3(0, 1, 0)), 3.0f);
    return s;
  };
  SceneSetup setup;
  setup.width = 40, setup.height = 30;
  setup.env = "0.8,0.9,1";
  IntegratorSettings integ;
  integ.filter = TextureFilter::brdf;
  const Film a = test::render_scene(make(), setup, 8, integ, 1);
  const Film b = test::render_scene(make(), setup, 8, integ, 2);
  ASSERT_EQ(a.radiance_sum.size(), b.radiance_sum.size());
  EXPECT_EQ(std::memcmp(a.radiance_sum.data(), b.radiance_sum.data(), a.radiance_sum.size() * sizeof(glm::dvec3)), 0);
  const Film c = test::render_scene(make(), setup, 8, integ, 2, 8);
  EXPECT_NE(std::memcmp(a.radiance_sum.data(), c.radiance_sum.data(), a.radiance_sum.size() * sizeof(glm::dvec3)), 0);
}

// The MIP-level AOV is the level the filters read: log2 of the footprint's (minor) width in texels.
// Head-on, 8 texels per pixel: 3; with the default footprint scale 1/√spp at 4 spp (1/2) one level
// less, at 64 spp (1/8) three less; under a KHR_texture_transform scale of 2, one more.
TEST(MipFilters, MipLevelAovReflectsTheFootprint) {
  struct Case {
    int spp;
    float scale;  // 0: render() chooses
    float uv_scale;
    float level;
  };
  for (const Case& k : {Case{1, 1.0f, 1.0f, 3.0f}, Case{4, 0.0f, 1.0f, 2.0f}, Case{64, 0.0f, 1.0f, 0.0f},
                        Case{1, 1.0f, 2.0f, 4.0f}}) {
    Scene s = periodic_quad();
    for (TextureRef* r : {&s.materials[0].base_color_texture, &s.materials[0].metallic_roughness_texture,
                          &s.materials[0].normal_texture})
      r->transform = TextureTransform::make({0.0f, 0.0f}, 0.0f, {k.uv_scale, k.uv_scale});
    const Image level = render_quad(std::move(s), TextureFilter::brdf, k.spp, {0, 0, 1}, k.scale, 0, true).mip_level();
    for (const auto& [x, y] : {std::pair{3, 5}, std::pair{16, 16}, std::pair{30, 29}})
      EXPECT_NEAR(level.at(x, y, 0), k.level, 1e-3f) << "spp " << k.spp << ", uv scale " << k.uv_scale;
  }
}

// --- lookups, without rendering ---------------------------------------------------------------

// level0 and brdf agree exactly on the same texel: at a texel's centre with no footprint the filter
// has one tap, and brdf returns the very lobe level0 does; off-centre, whichever of the four
// bilinear neighbours brdf selects, its lobe is level0's at that neighbour's centre.
TEST(MipFilters, Level0AndBrdfAgreeExactlyAtLevel0) {
  Rng rng(5, 2);
  const TexelSpec choices[5] = {kA, kB, kC, kD, kE};
  std::vector<int> pick(16 * 16);
  for (int& k : pick) k = int(rng.next_u32() % 5);
  Prepared p(textured_quad(16, [&](int i, int j) { return choices[pick[std::size_t(j) * 16 + i]]; }));
  p.mips->prepare(TextureFilter::brdf);
  const MaterialMip* mip = p.mips->find(0);
  ASSERT_NE(mip, nullptr);
  MipTexture::Scratch s0, s1;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i) {
      const Footprint centre{{(i + 0.5f) / 16, (j + 0.5f) / 16}, {0, 0}, {0, 0}};
      const auto l0 = mip->texture().lobes(TextureFilter::level0, centre, Rgb(1), 0.0f, s0);
      for (float u : {0.0f, 0.5f, 0.999f})
        EXPECT_TRUE(same_lobes(mip->texture().lobes(TextureFilter::brdf, centre, Rgb(1), u, s1), l0)) << i << "," << j;
      // And it is f_eff of that texel, as the closed form has it.
      const TexelSpec& t = choices[pick[std::size_t(j) * 16 + i]];
      const LobeMixtureBsdf b(l0);
      const glm::dvec3 want = f_eff(t, kWi, tilted(30, 200));
      const glm::dvec3 got(b.eval(kWi, tilted(30, 200)));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-4 * std::max(want[c], 1.0)) << i << "," << j;
    }
  for (int n = 0; n < 200; ++n) {
    const Footprint f{{rng.next_float(), rng.next_float()}, {0.01f, 0}, {0, 0.01f}};  // magnified: level 0
    const auto got = mip->texture().lobes(TextureFilter::brdf, f, Rgb(1), rng.next_float(), s1);
    bool found = false;
    for (int dj = -1; dj <= 1 && !found; ++dj)
      for (int di = -1; di <= 1 && !found; ++di) {
        const int i = int(std::floor(f.uv.x * 16)) + di, j = int(std::floor(f.uv.y * 16)) + dj;
        const Footprint c{{(i + 0.5f) / 16, (j + 0.5f) / 16}, {0, 0}, {0, 0}};
        found = same_lobes(got, mip->texture().lobes(TextureFilter::level0, c, Rgb(1), 0.0f, s0));
      }
    EXPECT_TRUE(found) << "uv " << f.uv.x << "," << f.uv.y;
  }
}

// KHR_materials_specular and KHR_materials_ior take part in every filter: on the periodic quad with a
// specular texture (A and D glossy, B and C nearly matte) and a specular colour texture (sRGB, as glTF
// stores it) and ior 1.6, a level-3 texel under `brdf` is the mean f_eff of the four texels as the
// renderer's glTF surface BSDF (appearance/gltf_surface_bsdf.h) shades them, and `param` is that
// BSDF with the four texels' mean parameters, mean specular weight and mean linear specular colour.
Scene specular_quad() {
  Scene s = periodic_quad();
  const int size = 256;
  Image spec(size, size, 4), color(size, size, 3);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const int k = (j % 2) * 2 + i % 2;  // A B / C D
      for (int c = 0; c < 3; ++c) spec.at(i, j, c) = 0.5f, color.at(i, j, c) = kSpecularSrgb[k][c];
      spec.at(i, j, 3) = kSpecularWeight[k];
    }
  MaterialDesc& m = s.materials[0];
  m.specular_texture.texture = test::add_image_texture(s, std::move(spec));
  m.specular_color_texture.texture = test::add_image_texture(s, std::move(color));
  m.specular = 0.9f;
  m.specular_color = Rgb(1.0f, 1.2f, 0.8f);
  m.ior = 1.6f;
  return s;
}

glm::dvec3 specular_f_eff(int k, const TexelSpec& t, const glm::vec3& wi, const glm::vec3& wo) {
  const glm::vec3 n = stored_normal(t.normal);
  if (glm::dot(n, wi) <= 0 || glm::dot(n, wo) <= 0) return glm::dvec3(0);
  ShadingParams p;
  p.base_color = linear(t.srgb), p.metallic = t.metallic, p.roughness = t.roughness, p.ior = 1.6f;
  p.specular = 0.9f * kSpecularWeight[k];
  p.specular_color = Rgb(1.0f, 1.2f, 0.8f) * linear(kSpecularSrgb[k]);
  const Frame f = Frame::from_normal(n);
  return glm::dvec3(SurfaceBsdf(p).eval(f.to_local(wi), f.to_local(wo))) * double(glm::dot(n, wi)) / double(wi.z);
}

TEST(MipFilters, SpecularLayerIsFiltered) {
  {
    Prepared p(specular_quad());
    EXPECT_NE(p.mips->find(0), nullptr);
    EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
  }
  const TexelSpec texels[4] = {kA, kB, kC, kD};
  for (const glm::vec3& wo : {glm::vec3(0, 0, 1), tilted(70, 200)}) {
    glm::dvec3 mean(0);
    for (int k = 0; k < 4; ++k) mean += specular_f_eff(k, texels[k], kWi, wo) / 4.0;
    const Image im = render_quad(specular_quad(), TextureFilter::brdf, 16, wo).radiance();
    expect_rgb_near(image_mean(im), kE0 * double(kWi.z) * mean, 5e-3, "brdf, view z " + std::to_string(wo.z));
    // param: one texel of the mean parameters (normal: the normalized mean).
    ShadingParams q;
    q.base_color = Rgb(0.0f), q.metallic = q.roughness = q.specular = 0.0f;
    glm::vec3 n(0);
    for (int k = 0; k < 4; ++k) {
      const TexelSpec& t = texels[k];
      q.base_color += linear(t.srgb) / 4.0f, q.metallic += t.metallic / 4, q.roughness += t.roughness / 4;
      q.specular += 0.9f * kSpecularWeight[k] / 4, n += stored_normal(t.normal);
    }
    q.specular_color = Rgb(0.0f);
    for (int k = 0; k < 4; ++k) q.specular_color += Rgb(1.0f, 1.2f, 0.8f) * linear(kSpecularSrgb[k]) / 4.0f;
    q.ior = 1.6f;
    n = glm::normalize(n);
    const Frame f = Frame::from_normal(n);
    const glm::dvec3 param = glm::dvec3(SurfaceBsdf(q).eval(f.to_local(kWi), f.to_local(wo))) * double(glm::dot(n, kWi)) / double(kWi.z);
    const Image pm = render_quad(specular_quad(), TextureFilter::param, 4, wo).radiance();
    expect_rgb_near(image_mean(pm), kE0 * double(kWi.z) * param, 2e-3, "param, view z " + std::to_string(wo.z));
    // The two differ here by more than the tolerances (the premise).
    EXPECT_GT(glm::length(mean - param), 0.02 * glm::length(mean));
  }
}

// One texel grid per material: a smaller texture whose size divides the largest is replicated
// (the nearest texel at any uv is unchanged); mappings that do not wrap with the grid where the
// surface reaches past it, and unmodelled extensions, leave the material to level0 with one warning
// naming why (mip_mapping_test.cpp: the mappings the grid serves).
TEST(MipFilters, TextureGridRules) {
  {
    Scene s = periodic_quad(8);
    s.images[0].pixels = Image(2, 4, 3);  // base color 2×4 against 8×8: factors 4 and 2
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 2; ++i) s.images[0].pixels.at(i, j, 0) = 0.1f + 0.1f * float(i + 2 * j);
    Prepared p(std::move(s));
    EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
    p.mips->prepare(TextureFilter::level0);
    const MaterialMip* mip = p.mips->find(0);
    ASSERT_NE(mip, nullptr);
    EXPECT_EQ(mip->texture().extent(), (Extent{8, 8}));
    const MaterialTexels level0 = mip->texture().level0_texels();
    Rng rng(3, 3);
    for (int n = 0; n < 100; ++n) {
      const glm::vec2 uv(rng.next_float() * 3 - 1, rng.next_float() * 3 - 1);
      const glm::ivec2 t = mip->texture().nearest_texel(uv);
      const float want = ColorConfig::builtin().srgb_texture_to_linear(
          0.1f + 0.1f * float(int(std::floor((uv.x - std::floor(uv.x)) * 2)) + 2 * int(std::floor((uv.y - std::floor(uv.y)) * 4))));
      EXPECT_FLOAT_EQ(level0.base_color[level0.index(t.x, t.y)].x, want) << uv.x << "," << uv.y;
    }
  }
  auto warned = [](Scene s, const std::string& why) {
    Prepared p(std::move(s));
    EXPECT_EQ(p.mips->find(0), nullptr) << why;
    const std::vector<std::string> w = p.mips->warnings(TextureFilter::param);
    ASSERT_EQ(w.size(), 1u) << why;
    EXPECT_NE(w[0].find(why), std::string::npos) << w[0];
    EXPECT_NE(w[0].find("materials[0]"), std::string::npos) << w[0];
    EXPECT_TRUE(p.mips->warnings(TextureFilter::level0).empty()) << "level0 filters nothing: nothing to say";
  };
  {
    // Sizes whose ratio is not whole take a grid of their common multiple (render/texel_grid.h).
    Scene s = periodic_quad(8);
    s.images[1].pixels = Image(3, 8, 3);
    Prepared p(std::move(s));
    EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
    p.mips->prepare(TextureFilter::level0);
    ASSERT_NE(p.mips->find(0), nullptr);
    EXPECT_EQ(p.mips->find(0)->texture().extent(), (Extent{24, 8}));
  }
  {
    Scene s = periodic_quad(8);
    s.materials[0].normal_texture.tex_coord = 1;
    warned(std::move(s), "TEXCOORD");
  }
  {
    Scene s = periodic_quad(8);
    s.materials[0].metallic_roughness_texture.transform = TextureTransform::make({0.5f, 0}, 0.3f, {1, 1});
    warned(std::move(s), "KHR_texture_transform");
  }
  {
    Scene s = periodic_quad(8);
    s.textures[2].sampler.wrap_s = WrapMode::clamp_to_edge;
    warned(std::move(s), "wrap mode");
  }
  {
    // A thin wall's transmission is filtered (mip_transmission_test.cpp); into a volume, refused.
    Scene s = periodic_quad(8);
    s.materials[0].transmission = 0.5f;
    s.materials[0].thickness = 0.1f;
    warned(std::move(s), "KHR_materials_transmission into a KHR_materials_volume");
  }
  {
    // A factor of 0 is no transmission (nor diffuse roughness), whatever its texture: filtered, no warning.
    Scene s = periodic_quad(8);
    s.materials[0].transmission_texture = s.materials[0].metallic_roughness_texture;
    s.materials[0].diffuse_roughness_texture = s.materials[0].metallic_roughness_texture;
    Prepared p(std::move(s));
    EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
    p.mips->prepare(TextureFilter::brdf);
    EXPECT_NE(p.mips->find(0), nullptr);
  }
  {
    // A tinted COLOR_0 makes the material's BRDF pyramid tintable, with no warning; white COLOR_0
    // does not.
    for (const float g : {0.5f, 1.0f}) {
      Scene s = periodic_quad(8);
      s.meshes[0].primitives[0].colors.assign(4, {1.0f, g, 1.0f, 1.0f});
      Prepared p(std::move(s));
      ASSERT_NE(p.mips->find(0), nullptr);
      EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
      p.mips->prepare(TextureFilter::brdf);
      EXPECT_EQ(p.mips->find(0)->texture().tintable(), g != 1.0f);
    }
  }
  {
    // Materials that differ only in what the texels do not hold share one build.
    Scene s = periodic_quad(8);
    s.materials.push_back(s.materials[0]);
    s.materials[1].alpha_mode = AlphaMode::blend;
    s.materials[1].emissive = Rgb(1.0f);
    s.materials.push_back(s.materials[0]);
    s.materials[2].roughness = 0.5f;
    Prepared p(std::move(s));
    EXPECT_EQ(p.mips->active_count(), 3);
    EXPECT_EQ(p.mips->distinct_count(), 2);
    EXPECT_EQ(p.mips->find(0), p.mips->find(1));
    EXPECT_NE(p.mips->find(0), p.mips->find(2));
  }
  {
    // Untextured: nothing to filter, nothing to say.
    Scene s = periodic_quad(8);
    s.materials[0] = test::lambertian(Rgb(0.5f));
    Prepared p(std::move(s));
    EXPECT_EQ(p.mips->find(0), nullptr);
    EXPECT_TRUE(p.mips->warnings(TextureFilter::brdf).empty());
  }
}

// The filter names svbrdf-render takes: level0, the mip module's parameter baselines, brdf.
TEST(MipFilters, FilterNames) {
  const std::vector<std::string> names = filter_names();
  for (const char* n : {"level0", "param", "toksvig", "vmf", "brdf"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n;
    ASSERT_TRUE(parse_filter(n).has_value());
    EXPECT_EQ(filter_name(*parse_filter(n)), n);
  }
  EXPECT_FALSE(parse_filter("trilinear").has_value());
}

}  // namespace
}  // namespace svbrdf

namespace svbrdf {
namespace {

// The geometric tangent frame the MIP lobes live in maps a tangent-space normal to the same world
// normal as apply_normal_map (the level0 path of non-MIP materials), on front and back faces, for
// both bitangent signs: the two ways of shading a normal map agree.
TEST(MipFilters, GeometricFrameMatchesTheNormalMap) {
  const glm::vec3 n_t = glm::normalize(glm::vec3(0.4f, -0.3f, 0.8f));
  Scene s;
  ImageDesc im;
  im.pixels = Image(1, 1, 3);
  for (int c = 0; c < 3; ++c) im.pixels.pixels[std::size_t(c)] = 0.5f * n_t[c] + 0.5f;
  s.images.push_back(std::move(im));
  TextureDesc t;
  t.image = 0;
  s.textures.push_back(t);
  MaterialDesc m;
  m.normal_texture.texture = 0;
  s.materials.push_back(m);
  MeshPrimitive prim;
  prim.tangents.assign(1, {1, 0, 0, 1});
  GeometryData g;
  g.prim = &prim;
  g.material = &s.materials[0];
  const TextureSet textures(s);
  const glm::vec3 n = glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f)), tangent(1.0f, 0.3f, -0.1f);
  for (bool front : {true, false})
    for (float sign : {1.0f, -1.0f}) {
      SurfacePoint sp;
      sp.geom = &g;
      sp.material = &s.materials[0];
      sp.front = front;
      sp.tangent = tangent;
      sp.bitangent_sign = sign;
      sp.ng = front ? n : -n;
      sp.shading = Frame::from_normal_tangent(sp.ng, glm::normalize(tangent));
      const Frame geo = geometric_frame(sp);
      apply_normal_map(sp, textures);
      const glm::vec3 a = geo.to_world(decode_normal(0.5f * n_t + 0.5f)), b = sp.shading.n;
      EXPECT_NEAR(glm::length(a - b), 0.0f, 1e-5f) << "front " << front << ", sign " << sign;
      EXPECT_NEAR(glm::dot(glm::cross(geo.s, geo.t), geo.n), sign * (front ? 1.0f : -1.0f) * 1.0f, 1e-5f);
    }
}

}  // namespace
}  // namespace svbrdf
