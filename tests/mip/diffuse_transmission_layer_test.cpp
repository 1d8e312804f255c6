// KHR_materials_diffuse_transmission in the BRDF MIP's lobes and exact reference
// (mip/diffuse_transmission.h): a level-0 lobe's diffuse BTDF against the extension's transcribed in
// double and against the renderer's glTF surface BSDF (appearance/gltf_surface_bsdf.h), with the
// specular layer, a thin-walled transmission, a sheen and a coat; what it leaves of the reflection; a
// coarse texel's exact reference as the mean of its texels'; the images' decoding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "appearance/frame.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/rng.h"
#include "base/error.h"
#include "exact_mean_check.h"
#include "gltf_transcription.h"
#include "mip/diffuse_transmission.h"
#include "mip/exact_reference.h"
#include "mip/gltf_material.h"
#include "random_directions.h"
#include "textures/color.h"
#include "textures/material_loader.h"

namespace svbrdf {
namespace {

using gltf_transcription::kPi;
using testing_directions::expect_coarse_exact_is_the_mean;
using testing_directions::random_above;

// A texel's parameters, each exactly a float.
struct Texel {
  glm::dvec3 base{0.5};
  double metallic = 0, roughness = 0.5, transmission = 0;
  glm::dvec3 normal{0, 0, 1};
  double specular = 1, ior = 1.5;  // KHR_materials_specular's factor, KHR_materials_ior
  glm::dvec3 specular_color{1.0};
  double share = 0;  // diffuseTransmission
  glm::dvec3 color{1.0};  // diffuseTransmissionColor
};

glm::dvec3 random_color(Rng& rng) { return {rng.next_float(), rng.next_float(), rng.next_float()}; }

Texel random_texel(Rng& rng) {
  Texel t;
  t.base = random_color(rng);
  t.metallic = rng.next_float() < 0.5f ? 0.0f : rng.next_float();
  t.roughness = 0.2f + 0.8f * rng.next_float();
  t.transmission = rng.next_float() < 0.5f ? 0.0f : rng.next_float();
  const float tilt = 0.5f * rng.next_float(), phi = 6.2831853f * rng.next_float();
  t.normal = glm::dvec3(glm::vec3(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt)));
  if (rng.next_float() < 0.5f) {
    t.specular = rng.next_float();
    t.ior = 1.2f + rng.next_float();
    t.specular_color = random_color(rng);
  }
  t.share = rng.next_float() < 0.25f ? 1.0f : rng.next_float();
  t.color = random_color(rng);
  return t;
}

SpecularLayer layer_of(const Texel& t) {
  SpecularLayer layer;
  layer.specular = float(t.specular), layer.ior = float(t.ior), layer.color = glm::vec3(t.specular_color);
  return layer;
}

Lobe lobe_of(const Texel& t) {
  Lobe l = lobe_from_texel(glm::vec3(t.base), float(t.metallic), float(t.roughness), glm::vec3(t.normal), 1.0f,
                           layer_of(t), {}, float(t.transmission));
  add_diffuse_transmission(l, float(t.metallic), layer_of(t), float(t.transmission),
                           DiffuseTransmissionLayer{float(t.share), glm::vec3(t.color)});
  return l;
}

// The diffuse transmission's f_eff transcribed in double from the extension's "Implementation" in the
// frame of the texel's normal n: diffuse_btdf(color = diffuseTransmissionColor) = C/π for light and view
// on opposite sides, mixed into the base by diffuseTransmission, the base under fresnel_mix's
// 1 − s·max(fr) of KHR_materials_specular (fr at n·wo, the renderer's choice for a pair without a half
// vector) and mixed with the specular BTDF by 1 − transmission, the dielectric weighted by 1 − metallic;
// f_eff = f·|n·wi|/|wi.z|.
glm::dvec3 diffuse_transmission_khr(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::dvec3 n = glm::normalize(t.normal);
  const double ci = glm::dot(n, wi), co = glm::dot(n, wo);
  if (wi.z >= 0 || wo.z <= 0 || ci >= 0 || co <= 0) return glm::dvec3(0);
  const double w = std::pow(1 - co, 5);
  const double q = (t.ior - 1) / (t.ior + 1);
  const glm::dvec3 f0 = glm::min(q * q * t.specular_color, glm::dvec3(1));
  const glm::dvec3 fr = f0 + (1.0 - f0) * w;
  const double base = 1 - t.specular * std::max({fr.r, fr.g, fr.b});
  return (1 - t.metallic) * (1 - t.transmission) * t.share * base * t.color / kPi * (-ci / -wi.z);
}

// The renderer's level-0 model in a frame about the texel's normal, f_eff = f·|n·wi|/|wi.z| for either
// side.
ShadingParams params_of(const Texel& t) {
  ShadingParams p;
  p.base_color = Rgb(t.base), p.metallic = float(t.metallic), p.roughness = float(t.roughness);
  p.transmission = float(t.transmission);
  p.specular = float(t.specular), p.ior = float(t.ior), p.specular_color = Rgb(t.specular_color);
  p.diffuse_transmission = float(t.share), p.diffuse_transmission_color = Rgb(t.color);
  return p;
}
glm::dvec3 f_eff_surface(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  const Frame f = Frame::from_normal(glm::normalize(glm::vec3(t.normal)));
  const SurfaceBsdf b(params_of(t));
  const double ci = glm::dot(glm::dvec3(f.n), wi);
  if (wo.z <= 0 || glm::dot(glm::dvec3(f.n), wo) <= 0 || (wi.z < 0) != (ci < 0)) return glm::dvec3(0);
  return glm::dvec3(b.eval(f.to_local(glm::vec3(wi)), f.to_local(glm::vec3(wo)))) * std::abs(ci) / std::abs(wi.z);
}

// At level 0 a lobe's diffuse transmission is the extension's: to 1e-6 relative in double against the
// transcription, in float to 1e-4; with its thin-walled transmission it is the renderer's BSDF below the
// surface, to 1e-4 (5e-4 below 1e-4, as the transmission's test), and its reflection, with ρ and ρ90
// less the transmitted share, the renderer's above.
TEST(DiffuseTransmissionLayer, Level0LobeIsTheExtensionsBtdf) {
  Rng rng(81, 1);
  int compared = 0, reflected = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Texel t = random_texel(rng);
    const Lobe l = lobe_of(t);
    ASSERT_TRUE(diffuse_transmits(l) || t.metallic == 1.0);
    glm::dvec3 wi = random_above(rng), wo = random_above(rng);
    wi.z = -wi.z;
    const glm::dvec3 want = diffuse_transmission_khr(t, wi, wo);
    const LobeShape<double> sd = lobe_shape<double>(l);
    const LobeShape<float> sf = lobe_shape<float>(l);
    const glm::dvec3 got = lobe_diffuse_transmission_eval<double>(l, sd, wi, wo);
    const glm::dvec3 in_float(lobe_diffuse_transmission_eval<float>(l, sf, glm::vec3(wi), glm::vec3(wo)));
    const glm::dvec3 both = got + lobe_transmission_eval<double>(l, sd, wi, wo), model = f_eff_surface(t, wi, wo);
    for (int c = 0; c < 3; ++c) {
      if (want[c] == 0) {
        EXPECT_EQ(got[c], 0.0) << trial;
        EXPECT_EQ(in_float[c], 0.0) << trial;
        continue;
      }
      EXPECT_NEAR(got[c], want[c], 1e-6 * want[c]) << trial;
      EXPECT_NEAR(in_float[c], want[c], 1e-4 * want[c]) << trial;
      const double tolerance = model[c] < 1e-4 ? 5e-4 : 1e-4;
      EXPECT_NEAR(both[c], model[c], tolerance * model[c]) << trial;
      ++compared;
    }
    wi.z = -wi.z;
    const glm::dvec3 r = lobe_eval<double>(l, pair_terms<double>(wi, wo)), rm = f_eff_surface(t, wi, wo);
    for (int c = 0; c < 3; ++c)
      if (rm[c] > 1e-4) {
        EXPECT_NEAR(r[c], rm[c], 1e-4 * rm[c]) << trial;
        ++reflected;
      }
  }
  EXPECT_GT(compared, 5000);
  EXPECT_GT(reflected, 5000);
}

// No share, no change: the lobe is bit for bit the one made without it, and transmits nothing diffusely.
TEST(DiffuseTransmissionLayer, NoShareLeavesTheLobeAsItWas) {
  Rng rng(82, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Texel t = random_texel(rng);
    t.share = 0;
    const Lobe l = lobe_of(t);
    const Lobe before = lobe_from_texel(glm::vec3(t.base), float(t.metallic), float(t.roughness), glm::vec3(t.normal), 1.0f,
                                        layer_of(t), {}, float(t.transmission));
    EXPECT_EQ(std::memcmp(&l, &before, sizeof(Lobe)), 0) << trial;
    EXPECT_FALSE(diffuse_transmits(l));
    EXPECT_EQ(lobe_diffuse_transmission_eval<double>(l, lobe_shape<double>(l), glm::normalize(glm::dvec3(0.3, 0.1, -0.9)),
                                                     glm::normalize(glm::dvec3(0.0, 0.2, 0.95))),
              glm::dvec3(0));
  }
}

// Texels of a material with a diffuse transmission (and, with `layers`, a sheen, a clear coat and a
// thin-walled transmission on some texels), per-texel arrays throughout.
MaterialTexels texels_of(const std::vector<Texel>& ts, int size, bool layers, Rng& rng) {
  MaterialTexels m(size, size);
  m.diffuse_transmission_factor = 1.0f, m.diffuse_transmission.resize(m.size());
  m.diffuse_transmission_color.resize(m.size());
  m.transmission_factor = 1.0f, m.transmission.resize(m.size());
  m.specular_factor = 1.0f, m.specular.resize(m.size()), m.specular_color.resize(m.size());
  if (layers) {
    m.clearcoat_factor = 1.0f, m.clearcoat.resize(m.size()), m.clearcoat_roughness_factor = 1.0f;
    m.clearcoat_roughness.resize(m.size());
    m.sheen_color_factor = glm::vec3(1.0f), m.sheen_color.resize(m.size()), m.sheen_roughness_factor = 1.0f;
    m.sheen_roughness.resize(m.size());
  }
  for (std::size_t k = 0; k < m.size(); ++k) {
    const Texel& t = ts[k];
    m.base_color[k] = glm::vec3(t.base), m.metallic[k] = float(t.metallic), m.roughness[k] = float(t.roughness);
    m.normal[k] = glm::vec3(t.normal);
    m.transmission[k] = float(t.transmission);
    m.specular[k] = float(t.specular), m.specular_color[k] = glm::vec3(t.specular_color);
    m.diffuse_transmission[k] = float(t.share), m.diffuse_transmission_color[k] = glm::vec3(t.color);
    if (layers) {
      m.clearcoat[k] = rng.next_float(), m.clearcoat_roughness[k] = 0.1f + 0.9f * rng.next_float();
      m.sheen_color[k] = glm::vec3(random_color(rng)), m.sheen_roughness[k] = 0.2f + 0.8f * rng.next_float();
    }
  }
  return m;
}

// Under a clear coat and a sheen, with a thin-walled transmission on some texels, a level-0 texel's
// exact reference below the surface is the renderer's surface BSDF: the lobe's two BTDFs under the
// sheen's albedo scaling at the mirrored pair and the coat's 1 − c·Fc(wo) (to 1e-4, 5e-4 below 1e-4).
// The texels' normals are the geometric one and the ior 1.5, so the surface's frame is the lobes'.
TEST(DiffuseTransmissionLayer, Level0UnderCoatAndSheenIsTheSurfaces) {
  Rng rng(83, 1);
  std::vector<Texel> ts;
  for (int k = 0; k < 16; ++k) {
    Texel t = random_texel(rng);
    t.normal = glm::dvec3(0, 0, 1), t.ior = 1.5;
    if (k % 4 == 1) t.share = 0;
    ts.push_back(t);
  }
  const MaterialTexels m = texels_of(ts, 4, true, rng);
  const ExactReference exact(m);
  int compared = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int i = trial % 4, j = (trial / 4) % 4;
    const std::size_t k = m.index(i, j);
    ShadingParams p = params_of(ts[k]);
    p.clearcoat = m.clearcoat[k], p.clearcoat_roughness = m.clearcoat_roughness[k];
    p.sheen_color = Rgb(m.sheen_color[k]), p.sheen_roughness = m.sheen_roughness[k];
    const SurfaceBsdf surface(p);
    glm::dvec3 wi = random_above(rng), wo = random_above(rng);
    wi.z = -wi.z;
    const glm::dvec3 want(surface.eval(glm::vec3(wi), glm::vec3(wo)));
    const glm::dvec3 got = exact.eval(0, i, j, wi, wo);
    for (int c = 0; c < 3; ++c) {
      if (want[c] == 0) {
        EXPECT_EQ(got[c], 0.0) << trial;
        continue;
      }
      const double tolerance = want[c] < 1e-4 ? 5e-4 : 1e-4;
      EXPECT_NEAR(got[c], want[c], tolerance * want[c]) << trial;
      ++compared;
    }
  }
  EXPECT_GT(compared, 6000);
}

// A coarse texel's exact reference below the surface is the mean of its texels' diffuse transmissions
// (transcribed; the texels' normals tilted, without a specular transmission, a coat or a sheen).
TEST(DiffuseTransmissionLayer, CoarseExactIsTheMeanOfTheTexels) {
  Rng rng(84, 1);
  std::vector<Texel> ts;
  for (int k = 0; k < 64; ++k) {
    Texel t = random_texel(rng);
    t.transmission = 0, t.ior = 1.5;  // (the material's one ior)
    ts.push_back(t);
  }
  const MaterialTexels m = texels_of(ts, 8, false, rng);
  expect_coarse_exact_is_the_mean(
      m, rng,
      [&](int x, int y, const glm::dvec3& wi, const glm::dvec3& wo) { return diffuse_transmission_khr(ts[m.index(x, y)], wi, wo); },
      true);
}

// The images decode as the renderer reads them (render/surface.cpp): the share from A times its factor
// within [0, 1], the colour from RGB (sRGB-encoded unless the image is linear) times its factor; absent
// maps give the factors, and a factor of 0 no diffuse transmission at all. material_images names the
// slots by their glTF paths, which a refusal repeats.
TEST(DiffuseTransmissionLayer, DecodedFromTheMaterialsImages) {
  Image share(2, 1, 4), color(2, 1, 4);
  const float rgb[2][3] = {{0.5f, 0.25f, 1.0f}, {1.0f, 1.0f, 1.0f}};
  for (int i = 0; i < 2; ++i) {
    for (int c = 0; c < 3; ++c) color.at(i, 0, c) = rgb[i][c], share.at(i, 0, c) = 0.9f;
    color.at(i, 0, 3) = 0.1f;
  }
  share.at(0, 0, 3) = 0.5f, share.at(1, 0, 3) = 1.6f;  // a float image's A past 1
  MaterialImages in;
  in.diffuse_transmission = &share, in.diffuse_transmission_factor = 0.8f;
  in.diffuse_transmission_color = &color, in.diffuse_transmission_color_is_linear = true;
  in.diffuse_transmission_color_factor = glm::vec3(0.8f, 0.6f, 0.4f);
  MaterialTexels m = decode_material_texels(in);
  ASSERT_TRUE(m.has_diffuse_transmission());
  EXPECT_FLOAT_EQ(m.diffuse_transmission_layer(0).share, 0.4f);
  EXPECT_FLOAT_EQ(m.diffuse_transmission_layer(1).share, 1.0f);
  EXPECT_EQ(m.diffuse_transmission_layer(0).color, glm::vec3(0.4f, 0.15f, 0.4f));
  EXPECT_EQ(m.diffuse_transmission_layer(1).color, glm::vec3(0.8f, 0.6f, 0.4f));
  in.diffuse_transmission_color_is_linear = false;
  m = decode_material_texels(in);
  EXPECT_FLOAT_EQ(m.diffuse_transmission_layer(0).color.r, 0.8f * ColorConfig::builtin().srgb_texture_to_linear(0.5f));
  MaterialImages plain;
  plain.diffuse_transmission_factor = 0.3f, plain.diffuse_transmission_color_factor = glm::vec3(0.3f, 0.2f, 0.1f);
  const MaterialTexels p = decode_material_texels(plain);
  EXPECT_TRUE(p.diffuse_transmission.empty());
  EXPECT_FLOAT_EQ(p.diffuse_transmission_layer(0).share, 0.3f);
  EXPECT_EQ(p.diffuse_transmission_layer(0).color, glm::vec3(0.3f, 0.2f, 0.1f));
  in.diffuse_transmission_factor = 0.0f;
  EXPECT_FALSE(decode_material_texels(in).has_diffuse_transmission());

  MaterialDesc d;
  d.where = "materials[4]";
  d.diffuse_transmission = 0.5f;
  d.diffuse_transmission_texture.texture = 0;
  d.diffuse_transmission_color_texture.texture = 1;
  const Image wider(3, 1, 4);
  const MaterialImages named = material_images(
      d, [&](const TextureRef& r, bool) { return SlotImage{r.texture == 0 ? &share : &wider, true}; }, "scene.gltf: ");
  EXPECT_EQ(named.diffuse_transmission, &share);
  EXPECT_FLOAT_EQ(named.diffuse_transmission_factor, 0.5f);
  try {
    decode_material_texels(named);
    ADD_FAILURE() << "textures of different sizes were decoded";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "scene.gltf: materials[4].extensions.KHR_materials_diffuse_transmission.diffuseTransmissionColorTexture"),
              std::string::npos)
        << e.what();
  }
  d.diffuse_transmission = 0.0f;
  const MaterialImages none = material_images(
      d, [&](const TextureRef& r, bool) { return SlotImage{r.texture == 0 ? &share : &wider, true}; }, "scene.gltf: ");
  EXPECT_EQ(none.diffuse_transmission, nullptr);
  EXPECT_FALSE(decode_material_texels(none).has_diffuse_transmission());
}

}  // namespace
}  // namespace svbrdf
