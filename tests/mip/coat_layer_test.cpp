// The clear coat of KHR_materials_clearcoat in the BRDF MIP (mip/coat_layer.h): the exact reference of
// a coated texel against the extension's layering transcribed in double and against the renderer's
// glTF surface BSDF (appearance/gltf_surface_bsdf.h), a coarse texel's exact reference against the
// mean of those, its table against its evaluation, the parameter filter's texel as the coated material
// of the mean parameters, and the coat read from a glTF material's images.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "appearance/frame.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/rng.h"
#include "mip/exact_reference.h"
#include "mip/mip_data.h"
#include "exact_mean_check.h"
#include "gltf_transcription.h"
#include "random_directions.h"
#include "textures/material_loader.h"

namespace svbrdf {
namespace {

using gltf_transcription::ggx_vd;
using gltf_transcription::kPi;
using testing_directions::expect_coarse_exact_is_the_mean;
using testing_directions::expect_exact_table_is_its_evaluation;
using testing_directions::random_above;

// A coated texel's parameters.
struct Texel {
  glm::dvec3 base{0.5};
  double metallic = 0, roughness = 0.5;
  glm::dvec3 normal{0, 0, 1};
  double clearcoat = 1, coat_roughness = 0.1;
  glm::dvec3 coat_normal{0, 0, 1};
};

// f_eff of the texel, transcribed in double from glTF 2.0 Appendix B (metal_brdf, dielectric_brdf
// with the fresnel_mix of ior 1.5) and the KHR_materials_clearcoat text (fresnel_coat with
// clearcoat_brdf = V·D at the coat's roughness and normal, its Fresnel at the view's cosine to the
// coat normal), in the frame of the texel's normal n as brdf-mip.md defines f_eff:
//   f = (1 − c·Fc)·f_base + c·Fc·V_c·D_c,  Fc = 0.04 + 0.96·(1 − |wo·Nc|)^5,  f_eff = f·(n·wi)/wi.z.
glm::dvec3 f_eff_khr(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::dvec3 n = glm::normalize(t.normal), nc = glm::normalize(t.coat_normal);
  const double ci = glm::dot(n, wi), co = glm::dot(n, wo);
  if (wi.z <= 0 || wo.z <= 0 || ci <= 0 || co <= 0) return glm::dvec3(0);
  const glm::dvec3 h = glm::normalize(wi + wo);
  const double vd = ggx_vd(t.roughness, n, wi, wo);
  const double vh = std::abs(glm::dot(wo, h)), w = std::pow(1 - vh, 5);
  const glm::dvec3 metal = vd * (t.base + (1.0 - t.base) * w);
  const double fr = 0.04 + 0.96 * w;
  const glm::dvec3 dielectric = (1 - fr) * t.base / kPi + fr * vd;
  const glm::dvec3 base = glm::mix(dielectric, metal, t.metallic);
  const double fc = 0.04 + 0.96 * std::pow(1 - std::min(std::abs(glm::dot(wo, nc)), 1.0), 5);
  const bool coat_faces = glm::dot(nc, wi) > 0 && glm::dot(nc, wo) > 0;
  const double coat = coat_faces ? ggx_vd(t.coat_roughness, nc, wi, wo) : 0.0;
  return ((1 - t.clearcoat * fc) * base + glm::dvec3(t.clearcoat * fc * coat)) * ci / wi.z;
}

// The renderer's level-0 model: the glTF surface BSDF in a frame about the texel's normal, the coat's
// normal expressed in it.
glm::dvec3 f_eff_surface(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::vec3 n = glm::normalize(glm::vec3(t.normal));
  if (wi.z <= 0 || wo.z <= 0 || glm::dot(glm::dvec3(n), wi) <= 0 || glm::dot(glm::dvec3(n), wo) <= 0) return glm::dvec3(0);
  const Frame f = Frame::from_normal(n);
  ShadingParams p;
  p.base_color = Rgb(t.base), p.metallic = float(t.metallic), p.roughness = float(t.roughness);
  p.clearcoat = float(t.clearcoat), p.clearcoat_roughness = float(t.coat_roughness);
  p.clearcoat_normal = f.to_local(glm::vec3(t.coat_normal));
  const SurfaceBsdf bsdf(p);
  return glm::dvec3(bsdf.eval(f.to_local(glm::vec3(wi)), f.to_local(glm::vec3(wo)))) * double(glm::dot(n, glm::vec3(wi))) / wi.z;
}

glm::dvec3 tilted(Rng& rng, float max_tilt) {
  const float tilt = max_tilt * rng.next_float(), phi = 6.2831853f * rng.next_float();
  return glm::dvec3(glm::vec3(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt)));
}

// Texels whose parameters are exactly representable in the texel arrays (floats).
Texel random_texel(Rng& rng) {
  Texel t;
  t.base = {rng.next_float(), rng.next_float(), rng.next_float()};
  t.metallic = rng.next_float() < 0.3f ? 1.0f : rng.next_float() < 0.5f ? 0.0f : rng.next_float();
  t.roughness = 0.2f + 0.8f * rng.next_float();
  t.normal = tilted(rng, 0.5f);
  t.clearcoat = rng.next_float() < 0.2f ? 1.0f : rng.next_float();
  t.coat_roughness = rng.next_float() < 0.3f ? 0.0f : rng.next_float();
  t.coat_normal = tilted(rng, 0.4f);
  return t;
}

MaterialTexels texels_of(const std::vector<Texel>& ts, int size) {
  MaterialTexels m(size, size);
  m.clearcoat.resize(m.size());
  m.clearcoat_roughness.resize(m.size());
  m.clearcoat_normal.resize(m.size());
  m.clearcoat_factor = 1.0f;
  m.clearcoat_roughness_factor = 1.0f;
  for (std::size_t k = 0; k < m.size(); ++k) {
    const Texel& t = ts[k];
    m.base_color[k] = glm::vec3(t.base), m.metallic[k] = float(t.metallic), m.roughness[k] = float(t.roughness);
    m.normal[k] = glm::vec3(t.normal);
    m.clearcoat[k] = float(t.clearcoat), m.clearcoat_roughness[k] = float(t.coat_roughness);
    m.clearcoat_normal[k] = glm::vec3(t.coat_normal);
  }
  return m;
}

// At level 0 the exact reference is the extension's f_eff: to 1e-6 relative against the double
// transcription, and to float precision (1e-4; 1e-3 on a sharp coat) against the renderer's BSDF.
TEST(CoatLayer, Level0IsTheExtensionsLayering) {
  Rng rng(41, 1);
  std::vector<Texel> ts;
  for (int k = 0; k < 16; ++k) ts.push_back(random_texel(rng));
  const MaterialTexels m = texels_of(ts, 4);
  const ExactReference exact(m);
  int compared = 0, coated = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const int i = trial % 4, j = (trial / 4) % 4;
    const Texel& t = ts[m.index(i, j)];
    // Every other pair near the coat's mirror direction, where its lobe dominates.
    glm::dvec3 wi = random_above(rng), wo = random_above(rng);
    if (trial % 2) {
      const glm::dvec3 nc = glm::normalize(t.coat_normal);
      wo = glm::normalize(2 * glm::dot(wi, nc) * nc - wi + 0.05 * random_above(rng));
      if (wo.z <= 0.02) continue;
    }
    const glm::dvec3 want = f_eff_khr(t, wi, wo), model = f_eff_surface(t, wi, wo);
    const glm::dvec3 got = exact.eval(0, i, j, wi, wo);
    // The renderer works in float, the coat normal through a float frame: 1e-4; its h is 6e-8 rad off,
    // which a coat of α = 1e-3 turns into 2.4e-4 of D (its slope 4·θ/α² at θ ~ α).
    const double model_tolerance = t.coat_roughness < 0.2 ? 1e-3 : 1e-4;
    for (int c = 0; c < 3; ++c) {
      if (want[c] == 0) {
        EXPECT_EQ(got[c], 0.0);
        continue;
      }
      EXPECT_NEAR(got[c], want[c], 1e-6 * want[c]) << "texel " << i << "," << j;
      EXPECT_NEAR(got[c], model[c], model_tolerance * model[c]) << "texel " << i << "," << j;
      ++compared;
    }
    // Pairs where the coat reflects more than the base's tenth count as the coat's.
    Texel bare = t;
    bare.clearcoat = 0;
    coated += glm::length(want - f_eff_khr(bare, wi, wo)) > 0.1 * glm::length(want);
  }
  EXPECT_GT(compared, 8000);
  EXPECT_GT(coated, 500);
}

// A coarse texel's exact reference is the mean of its texels' layered f_eff.
TEST(CoatLayer, CoarseExactIsTheMeanOfTheTexels) {
  Rng rng(42, 1);
  std::vector<Texel> ts;
  for (int k = 0; k < 64; ++k) ts.push_back(random_texel(rng));
  const MaterialTexels m = texels_of(ts, 8);
  expect_coarse_exact_is_the_mean(m, rng, [&](int x, int y, const glm::dvec3& wi, const glm::dvec3& wo) {
    return f_eff_khr(ts[m.index(x, y)], wi, wo);
  });
}

// The reference's table over the metric's pairs (its own loop) is its evaluation at those pairs.
TEST(CoatLayer, ExactTableIsItsEvaluation) {
  Rng rng(43, 1);
  std::vector<Texel> ts;
  for (int k = 0; k < 16; ++k) ts.push_back(random_texel(rng));
  expect_exact_table_is_its_evaluation(texels_of(ts, 4));
}

// The parameter filter's texel (what svbrdf-bake eval and compare measure for `param`) is the coated
// material of the texels' mean parameters, coat included: at level 0 the texel itself, as the exact
// reference evaluates it; at a coarse level the extension's layering of the mean base colour, metallic,
// roughness and normal under the mean clearcoat, coat roughness and coat normal (normals normalized).
// The filter evaluates in float: 1e-5 of the double transcription, 1e-3 on a sharp coat (the tolerance
// of Level0IsTheExtensionsLayering); its table is its evaluation over the metric's pairs.
TEST(CoatLayer, ParamFilterTexelIsTheCoatedMeanMaterial) {
  Rng rng(44, 1);
  std::vector<Texel> ts;
  for (int k = 0; k < 16; ++k) ts.push_back(random_texel(rng));
  const MipData mip = build_mip(texels_of(ts, 4));
  const ExactReference exact(mip.level0);
  // The mean texel over level `level`'s texel (i, j), as the parameter pyramid holds it.
  const auto mean_texel = [&](int level, int i, int j) {
    const Coverage c = coverage(mip.extent(0), level, i, j);
    Texel m;
    m.base = glm::dvec3(0), m.metallic = 0, m.roughness = 0, m.normal = glm::dvec3(0);
    m.clearcoat = 0, m.coat_roughness = 0, m.coat_normal = glm::dvec3(0);
    for (int y = c.rows.begin; y < c.rows.end; ++y)
      for (int x = c.columns.begin; x < c.columns.end; ++x) {
        const Texel& t = ts[mip.level0.index(x, y)];
        m.base += t.base, m.metallic += t.metallic, m.roughness += t.roughness, m.normal += t.normal;
        m.clearcoat += t.clearcoat, m.coat_roughness += t.coat_roughness, m.coat_normal += t.coat_normal;
      }
    const double n = double(c.count());
    m.base /= n, m.metallic /= n, m.roughness /= n, m.clearcoat /= n, m.coat_roughness /= n;
    m.normal = glm::normalize(m.normal), m.coat_normal = glm::normalize(m.coat_normal);
    return m;
  };
  int compared = 0, coated = 0;
  for (const auto& [level, i, j] : {std::array{0, 1, 2}, std::array{0, 3, 0}, std::array{1, 1, 0}, std::array{2, 0, 0}}) {
    const Texel t = mean_texel(level, i, j);
    const double tolerance = t.coat_roughness < 0.2 ? 1e-3 : 1e-5;
    for (int trial = 0; trial < 400; ++trial) {
      glm::dvec3 wi = random_above(rng), wo = random_above(rng);
      if (trial % 2) {
        const glm::dvec3 nc = t.coat_normal;
        wo = glm::normalize(2 * glm::dot(wi, nc) * nc - wi + 0.05 * random_above(rng));
        if (wo.z <= 0.02) continue;
      }
      const glm::dvec3 got = texel_eval(mip, TextureFilter::param, level, i, j, wi, wo);
      const glm::dvec3 want = f_eff_khr(t, wi, wo);
      for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(got[c], want[c], tolerance * want[c] + 1e-9) << "level " << level << " texel " << i << "," << j;
        if (level == 0) {
          const double e = exact.eval(0, i, j, wi, wo)[c];
          EXPECT_NEAR(got[c], e, tolerance * e + 1e-9) << "level 0 texel " << i << "," << j;
        }
        compared += want[c] > 0;
      }
      Texel bare = t;
      bare.clearcoat = 0;
      coated += glm::length(want - f_eff_khr(bare, wi, wo)) > 0.1 * glm::length(want);
    }
    const BrdfTable table = texel_table(mip, TextureFilter::param, level, i, j);
    const DirectionGrid& g = DirectionGrid::get();
    for (int p = 0; p < DirectionGrid::kPairs; p += 11) {
      const glm::dvec3 e = texel_eval(mip, TextureFilter::param, level, i, j, g.direction(DirectionGrid::wi_index(p)),
                                      g.direction(DirectionGrid::wo_index(p)));
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(table[static_cast<std::size_t>(p)][c], e[c], 1e-9 + 1e-5 * e[c]) << "pair " << p;
    }
  }
  EXPECT_GT(compared, 3000);
  EXPECT_GT(coated, 200);
}

// The coat's images decode as the renderer reads them: weight from R, roughness from G, each times its
// factor and within [0, 1]; the normal map as the base's, with its own scale; absent maps give the
// factors and (0, 0, 1), and a zero weight no coat at all.
TEST(CoatLayer, DecodedFromTheMaterialsImages) {
  Image tex(2, 1, 3), nrm(2, 1, 3);
  const float rgb[2][3] = {{0.5f, 0.25f, 0.0f}, {1.0f, 1.0f, 1.0f}};
  for (int i = 0; i < 2; ++i)
    for (int c = 0; c < 3; ++c) tex.at(i, 0, c) = rgb[i][c];
  const float n[2][3] = {{0.5f, 0.5f, 1.0f}, {1.0f, 0.5f, 0.5f}};  // (0, 0, 1) and (1, 0, 0) before scaling
  for (int i = 0; i < 2; ++i)
    for (int c = 0; c < 3; ++c) nrm.at(i, 0, c) = n[i][c];
  MaterialImages in;
  in.clearcoat = &tex, in.clearcoat_factor = 0.8f;
  in.clearcoat_roughness = &tex, in.clearcoat_roughness_factor = 0.5f;
  in.clearcoat_normal = &nrm, in.clearcoat_normal_scale = 2.0f;
  const MaterialTexels m = decode_material_texels(in);
  ASSERT_TRUE(m.has_coat());
  EXPECT_FLOAT_EQ(m.coat_layer(0).weight, 0.4f);
  EXPECT_FLOAT_EQ(m.coat_layer(0).roughness, 0.125f);
  EXPECT_FLOAT_EQ(m.coat_layer(1).weight, 0.8f);
  EXPECT_FLOAT_EQ(m.coat_layer(1).roughness, 0.5f);
  EXPECT_NEAR(m.coat_layer(0).normal.z, 1.0f, 1e-6f);
  // (2·1 − 1)·2 = 2 along x, 0·2 along y, (2·0.5 − 1) = 0 along z: the unit x axis.
  EXPECT_NEAR(m.coat_layer(1).normal.x, 1.0f, 1e-6f);
  EXPECT_NEAR(m.coat_layer(1).normal.z, 0.0f, 1e-6f);
  MaterialImages plain;
  plain.clearcoat_factor = 0.3f, plain.clearcoat_roughness_factor = 0.6f;
  const MaterialTexels p = decode_material_texels(plain);
  EXPECT_FLOAT_EQ(p.coat_layer(0).weight, 0.3f);
  EXPECT_FLOAT_EQ(p.coat_layer(0).roughness, 0.6f);
  EXPECT_EQ(p.coat_layer(0).normal, glm::vec3(0, 0, 1));
  in.clearcoat_factor = 0.0f;
  EXPECT_FALSE(decode_material_texels(in).has_coat());
}

}  // namespace
}  // namespace svbrdf
