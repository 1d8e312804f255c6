// KHR_materials_anisotropy in the BRDF MIP's lobes (mip/lobe.h, "Stretched shapes"): a level-0 texel's
// lobe and exact reference against the extension's anisotropic GGX transcribed in double and against
// the renderer's glTF surface BSDF (appearance/gltf_surface_bsdf.h); every stretched shape against its
// isotropic shape at the unstretched slopes; a stretched two-point mixture against its two atoms as
// the extension's lobes; a coarse texel's reference against the mean of its texels, and its table over
// the metric's pairs against its evaluation.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "appearance/frame.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/rng.h"
#include "exact_mean_check.h"
#include "gltf_transcription.h"
#include "mip/exact_reference.h"
#include "random_directions.h"

namespace svbrdf {
namespace {

using gltf_transcription::anisotropic_vd;
using gltf_transcription::anisotropic_vd_alphas;
using gltf_transcription::kPi;
using testing_directions::expect_coarse_exact_is_the_mean;
using testing_directions::expect_exact_table_is_its_evaluation;
using testing_directions::random_above;

// A texel's parameters, each exactly a float (the texel arrays hold floats).
struct Texel {
  glm::dvec3 base{0.5};
  double metallic = 0, roughness = 0.5;
  glm::dvec3 normal{0, 0, 1};
  double strength = 0;
  glm::dvec2 dir{1, 0};
};

// f_eff of the texel transcribed in double: glTF 2.0 Appendix B's fresnel_mix of ior 1.5 and the
// metal's Schlick Fresnel over KHR_materials_anisotropy's V·D, in the frame of the texel's normal n,
// f_eff = f·(n·wi)/wi.z.
glm::dvec3 f_eff_khr(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::dvec3 n = glm::normalize(t.normal);
  const double ci = glm::dot(n, wi), co = glm::dot(n, wo);
  if (wi.z <= 0 || wo.z <= 0 || ci <= 0 || co <= 0) return glm::dvec3(0);
  const glm::dvec3 h = glm::normalize(wi + wo);
  const double vd = anisotropic_vd(t.roughness, t.strength, t.dir, n, wi, wo);
  const double w = std::pow(1 - std::abs(glm::dot(wo, h)), 5);
  const glm::dvec3 metal = vd * (t.base + (1.0 - t.base) * w);
  const double fr = 0.04 + 0.96 * w;
  return glm::mix((1 - fr) * t.base / kPi + fr * vd, metal, t.metallic) * ci / wi.z;
}

// The renderer's level-0 model: the glTF surface BSDF in a frame about the texel's normal, with the
// anisotropy direction expressed in it as render/surface.cpp expresses it (the tangent-plane direction
// in the shading frame, its x–y part normalized).
glm::dvec3 f_eff_surface(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::vec3 n = glm::normalize(glm::vec3(t.normal));
  if (wi.z <= 0 || wo.z <= 0 || glm::dot(glm::dvec3(n), wi) <= 0 || glm::dot(glm::dvec3(n), wo) <= 0) return glm::dvec3(0);
  const Frame f = Frame::from_normal(n);
  ShadingParams p;
  p.base_color = Rgb(t.base), p.metallic = float(t.metallic), p.roughness = float(t.roughness);
  p.anisotropy = float(t.strength);
  const glm::vec3 local = f.to_local(glm::vec3(float(t.dir.x), float(t.dir.y), 0.0f));
  p.anisotropy_direction = glm::normalize(glm::vec2(local.x, local.y));
  const SurfaceBsdf bsdf(p);
  return glm::dvec3(bsdf.eval(f.to_local(glm::vec3(wi)), f.to_local(glm::vec3(wo)))) * double(glm::dot(n, glm::vec3(wi))) / wi.z;
}

// Random texels: roughness from 0.05 (sharp) to 1, normals tilted up to 0.5 rad, strength 0, 1 or
// between, directions all round.
Texel random_texel(Rng& rng, double min_roughness) {
  Texel t;
  t.base = {rng.next_float(), rng.next_float(), rng.next_float()};
  t.metallic = rng.next_float() < 0.3f ? 1.0f : rng.next_float() < 0.5f ? 0.0f : rng.next_float();
  t.roughness = float(min_roughness) + float(1.0 - min_roughness) * rng.next_float();
  const float tilt = 0.5f * rng.next_float(), phi = 6.2831853f * rng.next_float();
  t.normal = glm::dvec3(glm::vec3(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt)));
  const float u = rng.next_float();
  t.strength = u < 0.15f ? 0.0f : u < 0.3f ? 1.0f : rng.next_float();
  const float psi = 6.2831853f * rng.next_float();
  t.dir = glm::dvec2(glm::vec2(std::cos(psi), std::sin(psi)));
  return t;
}

MaterialTexels texels_of(const std::vector<Texel>& ts, int size) {
  MaterialTexels m(size, size);
  m.anisotropy.resize(m.size());
  m.anisotropy_direction.resize(m.size());
  m.anisotropy_factor = 1.0f;
  for (std::size_t k = 0; k < m.size(); ++k) {
    const Texel& t = ts[k];
    m.base_color[k] = glm::vec3(t.base), m.metallic[k] = float(t.metallic), m.roughness[k] = float(t.roughness);
    m.normal[k] = glm::vec3(t.normal);
    m.anisotropy[k] = float(t.strength), m.anisotropy_direction[k] = glm::vec2(t.dir);
  }
  return m;
}

// At level 0 the exact reference is the extension's f_eff: to 1e-6 relative against the double
// transcription. In float, the lobe and the renderer's BSDF (roughness ≥ 0.2; sharper lobes against
// the transcription only) agree with it to 1e-4, or 5e-4 where f_eff is below 1e-4: far in the tails
// of strongly stretched lobes, rounding the directions to float moves f_eff that much (the two float
// evaluations agree with each other there to 1e-8).
TEST(AnisotropyLayer, Level0IsTheExtensionsLobe) {
  Rng rng(61, 1);
  std::vector<Texel> ts;
  for (int k = 0; k < 16; ++k) ts.push_back(random_texel(rng, k < 4 ? 0.05 : 0.2));
  const MaterialTexels m = texels_of(ts, 4);
  ASSERT_TRUE(m.has_anisotropy());
  const ExactReference exact(m);
  int compared = 0, stretched = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int i = trial % 4, j = (trial / 4) % 4;
    const Texel& t = ts[m.index(i, j)];
    const glm::dvec3 wi = random_above(rng), wo = random_above(rng);
    const glm::dvec3 want = f_eff_khr(t, wi, wo), got = exact.eval(0, i, j, wi, wo);
    const glm::dvec3 model = t.roughness >= 0.2 ? f_eff_surface(t, wi, wo) : want;
    // The lobe in float, as the renderer's mixture evaluates it (lobe_mixture_bsdf.h).
    const glm::dvec3 in_float(lobe_eval<float>(level0_lobe(m, m.index(i, j)), pair_terms<float>(glm::vec3(wi), glm::vec3(wo))));
    for (int c = 0; c < 3; ++c) {
      if (want[c] == 0) {
        EXPECT_EQ(got[c], 0.0);
        continue;
      }
      EXPECT_NEAR(got[c], want[c], 1e-6 * want[c]) << "texel " << i << "," << j;
      const double in_float_tolerance = want[c] < 1e-4 ? 5e-4 : 1e-4;
      EXPECT_NEAR(model[c], want[c], in_float_tolerance * want[c]) << "texel " << i << "," << j;
      EXPECT_NEAR(in_float[c], want[c], in_float_tolerance * want[c]) << "texel " << i << "," << j;
      ++compared;
    }
    // Pairs where the anisotropy moves f_eff by more than a tenth count as the stretch's.
    Texel iso = t;
    iso.strength = 0;
    stretched += glm::length(want - f_eff_khr(iso, wi, wo)) > 0.1 * glm::length(want);
  }
  EXPECT_GT(compared, 6000);
  EXPECT_GT(stretched, 600);
}

// The lobe's stretch frame, transcribed: t the direction projected onto n's tangent plane, b = n × t.
struct StretchFrame {
  glm::dvec3 n, t, b;
};
StretchFrame frame_of(const Lobe& l) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(l.normal)), d(glm::dvec2(l.stretch_dir), 0.0);
  const glm::dvec3 t = glm::normalize(d - n * glm::dot(n, d));
  return {n, t, glm::cross(n, t)};
}

// A random orientation of `l`: its mean normal within 0.4 rad of z, its stretch direction any, its
// stretch in [1, 1 + max_extra].
void orient_randomly(Lobe& l, Rng& rng, float max_extra) {
  const float tilt = 0.4f * rng.next_float(), phi = 6.2831853f * rng.next_float();
  l.normal = glm::vec3(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt));
  const float psi = 6.2831853f * rng.next_float();
  l.stretch_dir = glm::vec2(std::cos(psi), std::sin(psi));
  l.stretch = 1.0f + max_extra * rng.next_float();
}

// Every shape of lobe.h, stretched, is its isotropic shape at the unstretched slopes: with slopes
// m = (h·t, h·b)/(h·n), D_r(h)·(n·h)⁴ = D_1(h')·(n·h')⁴ where h' has slopes (m_t/√r, m_b·√r) — the
// slope density of the stretch S = diag(r, 1/r), det S = 1 (Heitz 2014, §5.3).
TEST(AnisotropyLayer, StretchedShapesAreTheIsotropicShapesOfStretchedSlopes) {
  Rng rng(62, 1);
  Lobe atom;
  atom.alpha2 = 0.02f;
  Lobe band = atom;
  band.alpha2_hi = 0.3f, band.ggx = 0.7f, band.skirt = 1.0f;
  Lobe two_point = band;
  two_point.skirt = 0.0f;
  Lobe core = atom;
  core.ggx = 0.6f, core.skirt = 3.0f;
  for (Lobe shape : {atom, band, two_point, core}) {
    shape.weight = 1.0f;
    for (int trial = 0; trial < 400; ++trial) {
      orient_randomly(shape, rng, 30.0f);
      Lobe iso = shape;
      iso.stretch = 1.0f;
      const StretchFrame f = frame_of(shape);
      const LobeShape<double> s = lobe_shape<double>(shape), s1 = lobe_shape<double>(iso);
      ASSERT_TRUE(s.stretched);
      ASSERT_FALSE(s1.stretched);
      const glm::dvec3 h = random_above(rng, 0.3);
      const double nh = glm::dot(f.n, h);
      if (nh <= 0.05) continue;
      const double mt = glm::dot(f.t, h) / nh, mb = glm::dot(f.b, h) / nh, r = shape.stretch;
      const glm::dvec3 h1 = glm::normalize(f.n + (mt / std::sqrt(r)) * f.t + (mb * std::sqrt(r)) * f.b);
      const double nh1 = glm::dot(f.n, h1);
      const double got = lobe_d(s, nh, glm::cross(s.n, h)) * std::pow(nh, 4);
      const double want = lobe_d(s1, nh1, glm::cross(s1.n, h1)) * std::pow(nh1, 4);
      EXPECT_NEAR(got, want, 1e-9 * want + 1e-300) << "shape " << shape.alpha2_hi << " " << shape.skirt;
    }
  }
}

// A stretched two-point mixture reflects its two atoms' specular terms, each the extension's
// anisotropic GGX with α_t·α_b = the atom's α² and α_t/α_b = r: D·V of the mixture weights each
// atom's V by its share of D at the half vector (lobe.h), which makes D·V = (1 − β)·D_l·V_l + β·D_h·V_h
// exactly, stretched V included.
TEST(AnisotropyLayer, StretchedTwoPointMixtureIsItsAtoms) {
  Rng rng(63, 1);
  Lobe l;
  l.weight = 1.0f;
  l.f0 = glm::vec3(1.0f);  // F = 1, ρ = 0: the specular term alone
  l.alpha2 = 0.01f, l.alpha2_hi = 0.2f, l.ggx = 0.35f, l.skirt = 0.0f;
  for (int trial = 0; trial < 500; ++trial) {
    orient_randomly(l, rng, 20.0f);
    const glm::dvec3 wi = random_above(rng), wo = random_above(rng);
    const glm::dvec3 n = glm::normalize(glm::dvec3(l.normal));
    const double ci = glm::dot(n, wi);
    if (ci <= 0 || glm::dot(n, wo) <= 0) continue;
    const double r = l.stretch;
    const auto vd = [&](double a2) {
      return anisotropic_vd_alphas(std::sqrt(a2 * r), std::sqrt(a2 / r), glm::dvec2(l.stretch_dir), n, wi, wo);
    };
    // The lobe's cosine factor is mean normal·wi (lobe.h), its float normal's length times ci.
    const double len = glm::length(glm::dvec3(l.normal));
    const double want = ((1 - double(l.ggx)) * vd(l.alpha2) + double(l.ggx) * vd(l.alpha2_hi)) * len * ci / wi.z;
    const double got = lobe_eval<double>(l, pair_terms<double>(wi, wo)).x;
    EXPECT_NEAR(got, want, 1e-9 * want) << "trial " << trial;
  }
}

// A coarse texel's exact reference is the mean of its anisotropic texels' f_eff.
TEST(AnisotropyLayer, CoarseExactIsTheMeanOfTheTexels) {
  Rng rng(64, 1);
  std::vector<Texel> ts;
  for (int k = 0; k < 64; ++k) ts.push_back(random_texel(rng, 0.1));
  const MaterialTexels m = texels_of(ts, 8);
  expect_coarse_exact_is_the_mean(m, rng, [&](int x, int y, const glm::dvec3& wi, const glm::dvec3& wo) {
    return f_eff_khr(ts[m.index(x, y)], wi, wo);
  });
}

// The reference's table over the metric's pairs (direction_grid.cpp's loop, whose plain-GGX path a
// stretched lobe must not take) is its evaluation at those pairs.
TEST(AnisotropyLayer, ExactTableIsItsEvaluation) {
  Rng rng(66, 1);
  std::vector<Texel> ts;
  for (int k = 0; k < 16; ++k) ts.push_back(random_texel(rng, 0.1));
  expect_exact_table_is_its_evaluation(texels_of(ts, 4));
}

}  // namespace
}  // namespace svbrdf
