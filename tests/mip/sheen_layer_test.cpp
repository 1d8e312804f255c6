// The sheen of KHR_materials_sheen in the exact reference of the BRDF MIP (mip/sheen_layer.h): a
// level-0 texel with a sheen (and a clear coat over it, on some) against the extension's layering
// transcribed in double and against the renderer's glTF surface BSDF (appearance/gltf_surface_bsdf.h),
// a coarse texel's reference against the mean of those, and its table against its evaluation.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "appearance/frame.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/rng.h"
#include "appearance/sheen.h"
#include "exact_mean_check.h"
#include "gltf_transcription.h"
#include "base/error.h"
#include "mip/exact_reference.h"
#include "mip/gltf_material.h"
#include "textures/color.h"
#include "textures/material_loader.h"
#include "random_directions.h"

namespace svbrdf {
namespace {

using gltf_transcription::ggx_vd;
using gltf_transcription::kPi;
using testing_directions::expect_coarse_exact_is_the_mean;
using testing_directions::expect_exact_table_is_its_evaluation;
using testing_directions::random_above;

// A texel's parameters.
struct Texel {
  glm::dvec3 base{0.5};
  double metallic = 0, roughness = 0.5;
  glm::dvec3 normal{0, 0, 1};
  glm::dvec3 sheen{0.0};
  double sheen_roughness = 0.5;
  double clearcoat = 0, coat_roughness = 0.1;
};

// f_eff of the texel transcribed in double from glTF 2.0 Appendix B (the base, with the fresnel_mix of
// ior 1.5) and the KHR_materials_sheen text: sheen_brdf = sheenColor·D·V with the Charlie
// D(θh) = (2 + 1/α)·sin(θh)^(1/α)/(2π) at α = max(sheenRoughness², the model's floor) and the
// appearance model's Charlie V (sheen_visibility), layered by
//   f = f_sheen + f_base·min(1 − max(sheenColor)·E(n·wo), 1 − max(sheenColor)·E(n·wi))
// with E the model's sheen albedo; the clear coat (coat normal (0, 0, 1)) over it by fresnel_coat; all
// in the frame of the texel's normal n, f_eff = f·(n·wi)/wi.z.
glm::dvec3 f_eff_khr(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::dvec3 n = glm::normalize(t.normal);
  const double ci = glm::dot(n, wi), co = glm::dot(n, wo);
  if (wi.z <= 0 || wo.z <= 0 || ci <= 0 || co <= 0) return glm::dvec3(0);
  const glm::dvec3 h = glm::normalize(wi + wo);
  const double vd = ggx_vd(t.roughness, n, wi, wo);
  const double w = std::pow(1 - std::abs(glm::dot(wo, h)), 5);
  const glm::dvec3 metal = vd * (t.base + (1.0 - t.base) * w);
  const double fr = 0.04 + 0.96 * w;
  glm::dvec3 f = glm::mix((1 - fr) * t.base / kPi + fr * vd, metal, t.metallic);
  const double alpha = std::max(t.sheen_roughness * t.sheen_roughness, double(kSheenMinAlpha));
  const double nh = glm::dot(n, h);
  const double d = (2 + 1 / alpha) * std::pow(std::max(0.0, 1 - nh * nh), 0.5 / alpha) / (2 * kPi);
  const double c = std::max(t.sheen.r, std::max(t.sheen.g, t.sheen.b));
  const float rs = float(t.sheen_roughness);
  const double s = std::clamp(std::min(1 - c * sheen_albedo(float(co), rs), 1 - c * sheen_albedo(float(ci), rs)), 0.0, 1.0);
  f = t.sheen * (d * sheen_visibility(ci, co, alpha)) + s * f;
  const glm::dvec3 nc(0, 0, 1);
  const double fc = 0.04 + 0.96 * std::pow(1 - std::min(std::abs(wo.z), 1.0), 5);
  const double coat = ggx_vd(t.coat_roughness, nc, wi, wo);
  return ((1 - t.clearcoat * fc) * f + glm::dvec3(t.clearcoat * fc * coat)) * ci / wi.z;
}

// The renderer's level-0 model: the glTF surface BSDF in a frame about the texel's normal.
glm::dvec3 f_eff_surface(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::vec3 n = glm::normalize(glm::vec3(t.normal));
  if (wi.z <= 0 || wo.z <= 0 || glm::dot(glm::dvec3(n), wi) <= 0 || glm::dot(glm::dvec3(n), wo) <= 0) return glm::dvec3(0);
  const Frame f = Frame::from_normal(n);
  ShadingParams p;
  p.base_color = Rgb(t.base), p.metallic = float(t.metallic), p.roughness = float(t.roughness);
  p.sheen_color = Rgb(t.sheen), p.sheen_roughness = float(t.sheen_roughness);
  p.clearcoat = float(t.clearcoat), p.clearcoat_roughness = float(t.coat_roughness);
  p.clearcoat_normal = f.to_local(glm::vec3(0, 0, 1));
  const SurfaceBsdf bsdf(p);
  return glm::dvec3(bsdf.eval(f.to_local(glm::vec3(wi)), f.to_local(glm::vec3(wo)))) * double(glm::dot(n, glm::vec3(wi))) / wi.z;
}

// Texels whose parameters are exactly representable in the texel arrays (floats); a coat on some
// (`coated`: the material has one, of weight 0 on a third of its texels).
Texel random_texel(Rng& rng, bool coated) {
  Texel t;
  t.base = {rng.next_float(), rng.next_float(), rng.next_float()};
  t.metallic = rng.next_float() < 0.3f ? 1.0f : rng.next_float() < 0.5f ? 0.0f : rng.next_float();
  t.roughness = 0.2f + 0.8f * rng.next_float();
  const float tilt = 0.5f * rng.next_float(), phi = 6.2831853f * rng.next_float();
  t.normal = glm::dvec3(glm::vec3(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt)));
  t.sheen = {rng.next_float(), rng.next_float(), rng.next_float()};
  t.sheen_roughness = rng.next_float();
  if (coated) {
    t.clearcoat = rng.next_float() < 0.33f ? 0.0f : rng.next_float();
    t.coat_roughness = 0.2f + 0.8f * rng.next_float();
  }
  return t;
}

// n random texels.
std::vector<Texel> random_texels(Rng& rng, int n, bool coated) {
  std::vector<Texel> ts;
  for (int k = 0; k < n; ++k) ts.push_back(random_texel(rng, coated));
  return ts;
}

MaterialTexels texels_of(const std::vector<Texel>& ts, int size, bool coated) {
  MaterialTexels m(size, size);
  m.sheen_color.resize(m.size());
  m.sheen_roughness.resize(m.size());
  m.sheen_color_factor = glm::vec3(1.0f);
  m.sheen_roughness_factor = 1.0f;
  if (coated) {
    m.clearcoat.resize(m.size());
    m.clearcoat_roughness.resize(m.size());
    m.clearcoat_factor = 1.0f;
    m.clearcoat_roughness_factor = 1.0f;
  }
  for (std::size_t k = 0; k < m.size(); ++k) {
    const Texel& t = ts[k];
    m.base_color[k] = glm::vec3(t.base), m.metallic[k] = float(t.metallic), m.roughness[k] = float(t.roughness);
    m.normal[k] = glm::vec3(t.normal);
    m.sheen_color[k] = glm::vec3(t.sheen), m.sheen_roughness[k] = float(t.sheen_roughness);
    if (coated) m.clearcoat[k] = float(t.clearcoat), m.clearcoat_roughness[k] = float(t.coat_roughness);
  }
  return m;
}

// At level 0 the exact reference is the extension's f_eff: to 1e-6 relative against the double
// transcription, and to float precision (1e-4) against the renderer's BSDF; with and without a coat.
TEST(SheenLayer, Level0IsTheExtensionsLayering) {
  Rng rng(51, 1);
  for (const bool coated : {false, true}) {
    const std::vector<Texel> ts = random_texels(rng, 16, coated);
    const MaterialTexels m = texels_of(ts, 4, coated);
    ASSERT_TRUE(m.has_sheen());
    const ExactReference exact(m);
    int compared = 0, sheened = 0;
    for (int trial = 0; trial < 2000; ++trial) {
      const int i = trial % 4, j = (trial / 4) % 4;
      const Texel& t = ts[m.index(i, j)];
      const glm::dvec3 wi = random_above(rng), wo = random_above(rng);
      const glm::dvec3 want = f_eff_khr(t, wi, wo), model = f_eff_surface(t, wi, wo);
      const glm::dvec3 got = exact.eval(0, i, j, wi, wo);
      for (int c = 0; c < 3; ++c) {
        if (want[c] == 0) {
          EXPECT_EQ(got[c], 0.0);
          continue;
        }
        EXPECT_NEAR(got[c], want[c], 1e-6 * want[c]) << "texel " << i << "," << j;
        EXPECT_NEAR(got[c], model[c], 1e-4 * model[c]) << "texel " << i << "," << j;
        ++compared;
      }
      // Pairs where the sheen moves f by more than a tenth count as the sheen's.
      Texel bare = t;
      bare.sheen = glm::dvec3(0);
      sheened += glm::length(want - f_eff_khr(bare, wi, wo)) > 0.1 * glm::length(want);
    }
    EXPECT_GT(compared, 4000);
    EXPECT_GT(sheened, 500);
  }
}

// A coarse texel's exact reference is the mean of its texels' layered f_eff.
TEST(SheenLayer, CoarseExactIsTheMeanOfTheTexels) {
  Rng rng(52, 1);
  const std::vector<Texel> ts = random_texels(rng, 64, true);
  const MaterialTexels m = texels_of(ts, 8, true);
  expect_coarse_exact_is_the_mean(m, rng, [&](int x, int y, const glm::dvec3& wi, const glm::dvec3& wo) {
    return f_eff_khr(ts[m.index(x, y)], wi, wo);
  });
}

// The reference's table over the metric's pairs (its own loop) is its evaluation at those pairs.
TEST(SheenLayer, ExactTableIsItsEvaluation) {
  Rng rng(53, 1);
  for (const bool coated : {false, true}) {
    const std::vector<Texel> ts = random_texels(rng, 16, coated);
    expect_exact_table_is_its_evaluation(texels_of(ts, 4, coated));
  }
}

// The sheen's images decode as the renderer reads them (render/surface.cpp): colour from RGB
// (sRGB-encoded unless the image is linear) times its factor, roughness from A times its factor within
// [0, 1]; absent maps give the factors, and a black colour factor no sheen at all. material_images names
// the slots by their glTF paths, which a refusal repeats.
TEST(SheenLayer, DecodedFromTheMaterialsImages) {
  Image color(2, 1, 4), rough(2, 1, 4);
  const float rgb[2][3] = {{0.5f, 0.25f, 1.0f}, {1.0f, 1.0f, 1.0f}};
  for (int i = 0; i < 2; ++i) {
    for (int c = 0; c < 3; ++c) color.at(i, 0, c) = rgb[i][c], rough.at(i, 0, c) = 0.0f;
    color.at(i, 0, 3) = 1.0f;
  }
  rough.at(0, 0, 3) = 0.5f, rough.at(1, 0, 3) = 1.0f;
  MaterialImages in;
  in.sheen_color = &color, in.sheen_color_is_linear = true, in.sheen_color_factor = glm::vec3(0.8f, 0.6f, 0.4f);
  in.sheen_roughness = &rough, in.sheen_roughness_factor = 0.5f;
  MaterialTexels m = decode_material_texels(in);
  ASSERT_TRUE(m.has_sheen());
  EXPECT_EQ(m.sheen_layer(0).color, glm::vec3(0.4f, 0.15f, 0.4f));
  EXPECT_FLOAT_EQ(m.sheen_layer(0).roughness, 0.25f);
  EXPECT_EQ(m.sheen_layer(1).color, glm::vec3(0.8f, 0.6f, 0.4f));
  EXPECT_FLOAT_EQ(m.sheen_layer(1).roughness, 0.5f);
  in.sheen_color_is_linear = false;
  m = decode_material_texels(in);
  EXPECT_FLOAT_EQ(m.sheen_layer(0).color.r, 0.8f * ColorConfig::builtin().srgb_texture_to_linear(0.5f));
  MaterialImages plain;
  plain.sheen_color_factor = glm::vec3(0.3f, 0.2f, 0.1f), plain.sheen_roughness_factor = 0.6f;
  const MaterialTexels p = decode_material_texels(plain);
  EXPECT_EQ(p.sheen_layer(0).color, glm::vec3(0.3f, 0.2f, 0.1f));
  EXPECT_FLOAT_EQ(p.sheen_layer(0).roughness, 0.6f);
  in.sheen_color_factor = glm::vec3(0.0f);
  EXPECT_FALSE(decode_material_texels(in).has_sheen());

  MaterialDesc d;
  d.where = "materials[3]";
  d.sheen_color = Rgb(1.0f);
  d.sheen_color_texture.texture = 0;
  d.sheen_roughness = 1.0f;
  d.sheen_roughness_texture.texture = 1;
  const Image wider(3, 1, 4);
  const MaterialImages named = material_images(
      d, [&](const TextureRef& r, bool) { return SlotImage{r.texture == 0 ? &color : &wider, true}; }, "scene.gltf: ");
  try {
    decode_material_texels(named);
    ADD_FAILURE() << "textures of different sizes were decoded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("scene.gltf: materials[3].extensions.KHR_materials_sheen.sheenRoughnessTexture"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace svbrdf
