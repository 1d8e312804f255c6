// The glTF surface BSDF's extension layers (appearance/gltf_surface_bsdf.h) against what the
// extensions' texts write, transcribed here in double: KHR_materials_clearcoat's fresnel_coat,
// KHR_materials_anisotropy's D_GGX_anisotropic / V_GGX_anisotropic, KHR_materials_sheen's albedo
// scaling and KHR_materials_iridescence's Fresnel mix (the sheen lobe and the film's Fresnel are
// appearance/sheen.h's and thin_film.h's, checked on their own); with closed forms (a coat over
// black at normal incidence reflects its F0 = 0.04), properties (reciprocity where the
// specification keeps it, energy) and χ² of the sampler against its density.
#include <gtest/gtest.h>

#include <cmath>

#include "appearance/dispersion.h"
#include "appearance/gltf.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/microfacet_distribution.h"
#include "appearance/rng.h"
#include "appearance/sheen.h"
#include "appearance/thin_film.h"
#include "chi2.h"
#include "test_models.h"

namespace svbrdf {
namespace {

using testing::direction_deg;
using glm::dvec3;

constexpr double kPiD = 3.14159265358979323846;

// The isotropic GGX D·V of glTF Appendix B in double, for a unit normal n.
double ggx_vd(double alpha, const dvec3& n, const dvec3& wi, const dvec3& wo) {
  const double ci = glm::dot(n, wi), co = glm::dot(n, wo);
  if (ci <= 0 || co <= 0) return 0;
  const dvec3 h = glm::normalize(wi + wo);
  const double a2 = alpha * alpha, nh = glm::dot(n, h);
  const double d = a2 / (kPiD * std::pow(nh * nh * (a2 - 1) + 1, 2));
  const double v = 0.5 / (co * std::sqrt(ci * ci * (1 - a2) + a2) + ci * std::sqrt(co * co * (1 - a2) + a2));
  return d * v;
}

// KHR_materials_anisotropy's "Implementation" section in double: at along the unit direction t,
// ab along b = n × t.
double anisotropic_vd(double at, double ab, const dvec3& t, const dvec3& b, const dvec3& n, const dvec3& wi,
                      const dvec3& wo) {
  const dvec3 h = glm::normalize(wi + wo);
  const double a2 = at * ab;
  const dvec3 f(ab * glm::dot(t, h), at * glm::dot(b, h), a2 * glm::dot(n, h));
  const double w2 = a2 / glm::dot(f, f);
  const double d = a2 * w2 * w2 / kPiD;
  const double gv = glm::dot(n, wi) * glm::length(dvec3(at * glm::dot(t, wo), ab * glm::dot(b, wo), glm::dot(n, wo)));
  const double gl = glm::dot(n, wo) * glm::length(dvec3(at * glm::dot(t, wi), ab * glm::dot(b, wi), glm::dot(n, wi)));
  return d * 0.5 / (gv + gl);
}

// Directions above the horizon on a spread of angles, away from the exact pole.
std::vector<glm::vec3> directions() {
  std::vector<glm::vec3> out;
  for (double theta : {3.0, 30.0, 55.0, 80.0})
    for (double phi : {10.0, 100.0, 200.0, 290.0}) out.push_back(direction_deg(theta, phi));
  return out;
}

double rel_err(double a, double b) { return std::abs(a - b) / std::max(std::abs(b), 1e-30); }

// The surface is the plain glTF BRDF of g (appearance/gltf.h), channel by channel, within `tolerance`.
void expect_is_gltf_brdf(const SurfaceBsdf& b, const GltfParams& g, double tolerance) {
  for (const glm::vec3& wi : directions())
    for (const glm::vec3& wo : directions())
      for (int c = 0; c < 3; ++c) EXPECT_LT(rel_err(b.eval(wi, wo)[c], gltf_eval(g, wi, wo)[c]), tolerance);
}

// The sampler's χ² test against its own density at each view elevation (degrees), azimuth phi.
void expect_sampler_matches(const Bsdf& b, std::initializer_list<double> thetas, double phi) {
  for (const double theta : thetas) {
    const testing::Chi2Result r = testing::chi2_test(b, direction_deg(theta, phi));
    EXPECT_GT(r.p_value, 1e-3) << "θo " << theta << ": worst bin " << r.worst;
  }
}

// Directional albedo ∫ f cosθi dωi at wo by the model's own sampler (f cosθ / pdf per sample):
// unbiased for any sampler whose density covers f.
double albedo(const Bsdf& b, const glm::vec3& wo, int n, std::uint64_t seed, double* stderr_out = nullptr) {
  Rng rng(seed, 3);
  double sum = 0, sum2 = 0;
  for (int k = 0; k < n; ++k) {
    const BsdfSample s = b.sample(wo, SampleU(rng.next_float(), rng.next_float(), rng.next_float()));
    const double x = s.kind == SampleKind::absorbed ? 0.0 : double(max_channel(s.weight));
    sum += x, sum2 += x * x;
  }
  const double mean = sum / n;
  if (stderr_out) *stderr_out = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
  return mean;
}

// A clear coat over a black base (no diffuse, no specular layer) seen head-on reflects the coat's
// Fresnel at normal incidence, ((1.5 − 1)/(1.5 + 1))² = 0.04, when the coat is smooth.
TEST(Clearcoat, OverBlackAtNormalIncidenceReflectsItsF0) {
  ShadingParams p;
  p.base_color = Rgb(0.0f);
  p.specular = 0.0f;
  p.clearcoat = 1.0f;
  p.clearcoat_roughness = 0.0f;
  const SurfaceBsdf b(p);
  EXPECT_NEAR(albedo(b, {0, 0, 1}, 20000, 1), 0.04, 1e-4);
  // Half the coat reflects half as much.
  p.clearcoat = 0.5f;
  EXPECT_NEAR(albedo(SurfaceBsdf(p), {0, 0, 1}, 20000, 2), 0.02, 1e-4);
}

// eval is the extension's fresnel_coat: mix(material, coat V·D, clearcoat·Fc(|wo·Nc|)), the
// material being the plain glTF BRDF (appearance/gltf.h) and the coat normal tilted off the base's.
TEST(Clearcoat, EvalIsFresnelCoatOverTheGltfBrdf) {
  ShadingParams p;
  p.base_color = Rgb(0.7f, 0.3f, 0.1f);
  p.metallic = 0.4f;
  p.roughness = 0.45f;
  p.clearcoat = 0.8f;
  p.clearcoat_roughness = 0.3f;
  p.clearcoat_normal = glm::normalize(glm::vec3(0.15f, -0.1f, 1.0f));
  const SurfaceBsdf b(p);
  const GltfParams g{p.base_color, p.metallic, p.roughness};
  const dvec3 nc(p.clearcoat_normal);
  const double ac = 0.3 * 0.3;
  for (const glm::vec3& wi : directions())
    for (const glm::vec3& wo : directions()) {
      const double fc = 0.04 + 0.96 * std::pow(1.0 - std::abs(glm::dot(dvec3(wo), nc)), 5.0);
      const double blend = 0.8 * fc;
      const dvec3 base(gltf_eval(g, wi, wo));
      const dvec3 want = (1.0 - blend) * base + blend * ggx_vd(ac, nc, dvec3(wi), dvec3(wo));
      const dvec3 got(b.eval(wi, wo));
      for (int c = 0; c < 3; ++c) EXPECT_LT(rel_err(got[c], want[c]), 2e-5) << "channel " << c;
    }
}

// Coat and base together never reflect more than arrives: a white Lambertian base (the specular
// layer off: the glTF base's own fresnel_mix reflects up to 14 % more than arrives at grazing views)
// under a coat of any roughness, in a white furnace.
TEST(Clearcoat, WhiteFurnaceNeverAboveOne) {
  for (float rough : {0.0f, 0.3f, 1.0f})
    for (double theta : {0.0, 45.0, 75.0, 88.0}) {
      ShadingParams p;
      p.base_color = Rgb(1.0f);
      p.specular = 0.0f;
      p.clearcoat = 1.0f;
      p.clearcoat_roughness = rough;
      double se = 0;
      const double a = albedo(SurfaceBsdf(p), direction_deg(theta, 30.0), 200000, 5, &se);
      EXPECT_LE(a, 1.0 + 1e-5 + 3 * se) << "coat roughness " << rough << " at " << theta << "°";
      EXPECT_GT(a, 0.5);
    }
}

TEST(Clearcoat, SamplerMatchesItsDensity) {
  ShadingParams p;
  p.base_color = Rgb(0.6f, 0.4f, 0.2f);
  p.roughness = 0.6f;
  p.clearcoat = 1.0f;
  p.clearcoat_roughness = 0.2f;
  p.clearcoat_normal = glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f));
  const SurfaceBsdf b(p);
  expect_sampler_matches(b, {20.0, 70.0}, 40.0);
}

// With αt = αb the anisotropic D and Λ are the isotropic ones; with strength 0 the surface is
// the plain glTF BRDF whatever the direction (to float rounding: gltf_eval writes F0 = 0.04 where
// the surface computes ((ior − 1)/(ior + 1))²).
TEST(Anisotropy, ZeroStrengthIsIsotropicGgx) {
  for (float a : {0.01f, 0.2f, 0.9f})
    for (const glm::vec3& w : directions()) {
      EXPECT_LT(rel_err(ggx_d(glm::vec2(a), w), ggx_d(a, w)), 1e-5);
      EXPECT_LT(rel_err(ggx_lambda(glm::vec2(a), w), ggx_lambda(a, w)), 1e-5);
    }
  ShadingParams p;
  p.base_color = Rgb(0.8f, 0.5f, 0.2f);
  p.metallic = 0.5f;
  p.roughness = 0.35f;
  p.anisotropy = 0.0f;
  p.anisotropy_direction = glm::vec2(0.6f, 0.8f);
  expect_is_gltf_brdf(SurfaceBsdf(p), {p.base_color, p.metallic, p.roughness}, 1e-6);
}

// A white metal's BRDF is the specular V·D alone (Fresnel 1): it must be the extension's
// anisotropic V·D with αt = mix(α, 1, strength²) along the direction and α across it.
TEST(Anisotropy, EvalIsTheExtensionsAnisotropicGgx) {
  for (float strength : {0.3f, 0.9f})
    for (float rough : {0.2f, 0.6f}) {
      ShadingParams p;
      p.base_color = Rgb(1.0f);
      p.metallic = 1.0f;
      p.roughness = rough;
      p.anisotropy = strength;
      const double angle = 0.7;
      p.anisotropy_direction = glm::vec2(std::cos(angle), std::sin(angle));
      const SurfaceBsdf b(p);
      const double alpha = double(rough) * rough;
      const double at = alpha + (1 - alpha) * double(strength) * strength;
      const dvec3 t(std::cos(angle), std::sin(angle), 0), n(0, 0, 1), bt = glm::cross(n, t);
      for (const glm::vec3& wi : directions())
        for (const glm::vec3& wo : directions()) {
          const double want = anisotropic_vd(at, alpha, t, bt, n, dvec3(wi), dvec3(wo));
          EXPECT_LT(rel_err(b.eval(wi, wo).x, want), 2e-5) << "strength " << strength << " roughness " << rough;
        }
    }
}

// ∫ D(h) cosθh dωh = 1 for anisotropic GGX (midpoint quadrature on θ, φ in double).
TEST(Anisotropy, DistributionIsNormalized) {
  for (const glm::vec2 a : {glm::vec2(0.3f, 0.1f), glm::vec2(0.9f, 0.2f)}) {
    const int nt = 2000, np = 400;
    double sum = 0;
    for (int i = 0; i < nt; ++i) {
      const double th = (i + 0.5) / nt * kPiD / 2;
      for (int j = 0; j < np; ++j) {
        const double ph = (j + 0.5) / np * 2 * kPiD;
        const glm::vec3 h(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th));
        sum += ggx_d(a, h) * std::cos(th) * std::sin(th);
      }
    }
    EXPECT_NEAR(sum * (kPiD / 2 / nt) * (2 * kPiD / np), 1.0, 2e-3) << a.x << ", " << a.y;
  }
}

TEST(Anisotropy, ReciprocalAndEnergyBounded) {
  ShadingParams p;
  p.base_color = Rgb(1.0f);
  p.metallic = 1.0f;
  p.roughness = 0.4f;
  p.anisotropy = 0.8f;
  p.anisotropy_direction = glm::vec2(0.0f, 1.0f);
  const SurfaceBsdf b(p);
  for (const glm::vec3& wi : directions())
    for (const glm::vec3& wo : directions()) EXPECT_LT(rel_err(b.eval(wi, wo).x, b.eval(wo, wi).x), 1e-5);
  for (double theta : {0.0, 45.0, 80.0}) {
    double se = 0;
    EXPECT_LE(albedo(b, direction_deg(theta, 60.0), 200000, 9, &se), 1.0 + 3 * se);
  }
}

TEST(Anisotropy, SamplerMatchesItsDensity) {
  ShadingParams p;
  p.base_color = Rgb(0.9f, 0.7f, 0.5f);
  p.metallic = 0.7f;
  p.roughness = 0.3f;
  p.anisotropy = 0.7f;
  p.anisotropy_direction = glm::normalize(glm::vec2(1.0f, 2.0f));
  const SurfaceBsdf b(p);
  expect_sampler_matches(b, {10.0, 60.0}, 120.0);
}

// KHR_materials_sheen: sheen_brdf + material·min(1 − max(color)·E(wo), 1 − max(color)·E(wi)), the
// material being the glTF BRDF; E from the sheen's own albedo table.
TEST(Sheen, EvalIsTheAlbedoScaledLayerOverTheGltfBrdf) {
  ShadingParams p;
  p.base_color = Rgb(0.2f, 0.5f, 0.7f);
  p.metallic = 0.2f;
  p.roughness = 0.6f;
  p.sheen_color = Rgb(0.9f, 0.4f, 0.3f);
  p.sheen_roughness = 0.5f;
  const SurfaceBsdf b(p);
  const GltfParams g{p.base_color, p.metallic, p.roughness};
  for (const glm::vec3& wi : directions())
    for (const glm::vec3& wo : directions()) {
      const double scale = std::min(1.0 - 0.9 * sheen_albedo(wo.z, 0.5f), 1.0 - 0.9 * sheen_albedo(wi.z, 0.5f));
      const dvec3 want = dvec3(sheen_brdf(wi, wo, p.sheen_color, 0.5f)) + scale * dvec3(gltf_eval(g, wi, wo));
      const dvec3 got(b.eval(wi, wo));
      for (int c = 0; c < 3; ++c) EXPECT_LT(rel_err(got[c], want[c]), 2e-5) << "channel " << c;
    }
}

// Sheen over a white Lambertian base keeps a white furnace at or below one; its sampler matches
// its density.
TEST(Sheen, WhiteFurnaceAndSampler) {
  ShadingParams p;
  p.base_color = Rgb(1.0f);
  p.specular = 0.0f;
  p.sheen_color = Rgb(1.0f);
  p.sheen_roughness = 0.4f;
  const SurfaceBsdf b(p);
  for (double theta : {0.0, 60.0, 85.0}) {
    double se = 0;
    EXPECT_LE(albedo(b, direction_deg(theta, 0.0), 200000, 13, &se), 1.0 + 0.005 + 3 * se) << theta;
  }
  expect_sampler_matches(b, {30.0, 75.0}, 0.0);
}

// KHR_materials_iridescence: both Fresnel terms become mix(Schlick, F_film, iridescence), the film
// at |wo·h|, on the dielectric's F0 from ior and on the metal's base color.
TEST(Iridescence, EvalMixesTheFilmIntoBothFresnelTerms) {
  ShadingParams p;
  p.base_color = Rgb(0.9f, 0.6f, 0.3f);
  p.metallic = 0.5f;
  p.roughness = 0.4f;
  p.iridescence = 0.7f;
  p.iridescence_ior = 1.6f;
  p.iridescence_thickness = 350.0f;
  const SurfaceBsdf b(p);
  const Rgb f0(0.04f);
  for (const glm::vec3& wi : directions())
    for (const glm::vec3& wo : directions()) {
      const dvec3 h = glm::normalize(dvec3(wi) + dvec3(wo));
      const double c = std::abs(glm::dot(dvec3(wo), h)), w = std::pow(1.0 - c, 5.0);
      const double s = ggx_vd(0.16, {0, 0, 1}, dvec3(wi), dvec3(wo));
      const dvec3 film_d(iridescence_fresnel(float(c), 350.0f, 1.6f, f0));
      const dvec3 film_m(iridescence_fresnel(float(c), 350.0f, 1.6f, p.base_color));
      const dvec3 fd = glm::mix(dvec3(0.04 + 0.96 * w), film_d, 0.7);
      const dvec3 base(p.base_color);
      const dvec3 fm = glm::mix(base + (1.0 - base) * w, film_m, 0.7);
      const double fmax = std::max(fd.x, std::max(fd.y, fd.z));
      const dvec3 dielectric = (1.0 - fmax) * base / kPiD + fd * s;
      const dvec3 want = glm::mix(dielectric, s * fm, 0.5);
      const dvec3 got(b.eval(wi, wo));
      for (int k = 0; k < 3; ++k) EXPECT_LT(rel_err(got[k], want[k]), 1e-4) << "channel " << k;
    }
  // With no film thickness the film is the plain Fresnel: the surface is the glTF BRDF.
  p.iridescence_thickness = 0.0f;
  expect_is_gltf_brdf(SurfaceBsdf(p), {p.base_color, p.metallic, p.roughness}, 1e-5);
}

// KHR_materials_diffuse_transmission: base = mix(diffuse_brdf(baseColor), diffuse_btdf(color),
// diffuseTransmission) under the dielectric's 1 − specular·max(fr): reflection as the glTF BRDF with
// its Lambertian scaled by 1 − dt, transmission (wi below) (1 − fr(wo.z))·dt·color/π.
TEST(DiffuseTransmission, EvalIsTheExtensionsMixOfBrdfAndBtdf) {
  ShadingParams p;
  p.base_color = Rgb(0.3f, 0.6f, 0.2f);
  p.roughness = 0.5f;
  p.diffuse_transmission = 0.6f;
  p.diffuse_transmission_color = Rgb(0.9f, 0.8f, 0.1f);
  const SurfaceBsdf b(p);
  for (const glm::vec3& wi : directions())
    for (const glm::vec3& wo : directions()) {
      // Reflection: the glTF BRDF with ρ/π → (1 − dt)·ρ/π (α = 0.25, F0 = 0.04).
      const dvec3 h = glm::normalize(dvec3(wi) + dvec3(wo));
      const double fr = 0.04 + 0.96 * std::pow(1.0 - std::abs(glm::dot(dvec3(wo), h)), 5.0);
      const double s = ggx_vd(0.25, {0, 0, 1}, dvec3(wi), dvec3(wo));
      const dvec3 refl = (1 - fr) * 0.4 * dvec3(p.base_color) / kPiD + fr * s;
      // Transmission to the mirror of wi below the surface.
      const glm::vec3 below(wi.x, wi.y, -wi.z);
      const double ft = 0.04 + 0.96 * std::pow(1.0 - double(wo.z), 5.0);
      const dvec3 trans = (1 - ft) * 0.6 * dvec3(p.diffuse_transmission_color) / kPiD;
      for (int k = 0; k < 3; ++k) {
        EXPECT_LT(rel_err(b.eval(wi, wo)[k], refl[k]), 2e-5) << "reflection, channel " << k;
        EXPECT_LT(rel_err(b.eval(below, wo)[k], trans[k]), 2e-5) << "transmission, channel " << k;
      }
    }
}

// A white Lambertian base (the specular layer off) that transmits half of what it scatters keeps
// everything: directional albedo over both hemispheres 1, half of it transmitted; its sampler
// (both hemispheres) matches its density.
TEST(DiffuseTransmission, WhiteFurnaceAndSampler) {
  ShadingParams p;
  p.base_color = Rgb(1.0f);
  p.specular = 0.0f;
  p.diffuse_transmission = 0.5f;
  const SurfaceBsdf b(p);
  for (double theta : {0.0, 50.0, 85.0}) {
    Rng rng(23, 3);
    double all = 0, below = 0;
    const int n = 50000;
    for (int k = 0; k < n; ++k) {
      const BsdfSample smp = b.sample(direction_deg(theta, 10.0), SampleU(rng.next_float(), rng.next_float(), rng.next_float()));
      if (smp.kind == SampleKind::absorbed) continue;
      all += smp.weight.x;
      if (smp.wi.z < 0) below += smp.weight.x;
    }
    EXPECT_NEAR(all / n, 1.0, 1e-4) << theta;
    EXPECT_NEAR(below / n, 0.5, 0.01) << theta;
  }
  p.specular = 1.0f;
  p.base_color = Rgb(0.7f, 0.5f, 0.3f);
  p.diffuse_transmission_color = Rgb(0.4f, 0.9f, 0.6f);
  expect_sampler_matches(SurfaceBsdf(p), {20.0, 70.0}, 0.0);
}

// KHR_materials_transmission on a thin wall (no volume), its "Transmission BTDF": base =
// mix(diffuse_brdf, specular_btdf·baseColor, transmission) under the dielectric's 1 − specular·max(fr),
// specular_btdf = V·D at the transmission half vector H_T = normalize(V − 2(N·L)N + L), transcribed
// here: reflection as the glTF BRDF with ρ/π → (1 − T)·ρ/π, transmission (wi below)
// (1 − fr(|wo·H_T|))·T·baseColor·D(H_T)·V. V is the core BRDF's height-correlated Smith term (the
// extension's implementation notes, non-normative, write the separable one): the reflection lobe
// turned over.
TEST(Transmission, ThinWallIsTheExtensionsMicrofacetBtdf) {
  ShadingParams p;
  p.base_color = Rgb(0.3f, 0.6f, 0.2f);
  p.roughness = 0.5f;
  p.transmission = 0.7f;
  const SurfaceBsdf b(p);
  EXPECT_FALSE(b.has_impulse());
  const double a2 = 0.25 * 0.25;
  for (const glm::vec3& wi : directions())
    for (const glm::vec3& wo : directions()) {
      const dvec3 h = glm::normalize(dvec3(wi) + dvec3(wo));
      const double fr = 0.04 + 0.96 * std::pow(1.0 - std::abs(glm::dot(dvec3(wo), h)), 5.0);
      const dvec3 refl = (1 - fr) * 0.3 * dvec3(p.base_color) / kPiD + fr * ggx_vd(0.25, {0, 0, 1}, dvec3(wi), dvec3(wo));
      // L below the surface, V = wo, N = z.
      const dvec3 L(wi.x, wi.y, -wi.z), V(wo), N(0, 0, 1);
      const double nl = glm::dot(N, L), nv = glm::dot(N, V);
      const dvec3 ht = glm::normalize(V - 2 * nl * N + L);
      const double nh = glm::dot(N, ht);
      const double d = a2 / (kPiD * std::pow(nh * nh * (a2 - 1) + 1, 2));
      const double v = 0.5 / (nv * std::sqrt(nl * nl * (1 - a2) + a2) + -nl * std::sqrt(nv * nv * (1 - a2) + a2));
      const double ft = 0.04 + 0.96 * std::pow(1.0 - std::abs(glm::dot(V, ht)), 5.0);
      const dvec3 trans = (1 - ft) * 0.7 * dvec3(p.base_color) * d * v;
      for (int k = 0; k < 3; ++k) {
        EXPECT_LT(rel_err(b.eval(wi, wo)[k], refl[k]), 2e-5) << "reflection, channel " << k;
        EXPECT_LT(rel_err(b.eval(glm::vec3(L), wo)[k], trans[k]), 2e-5) << "transmission, channel " << k;
      }
    }
}

// What a white thin wall that transmits everything (no specular layer, so no Fresnel) lets through
// is what a white metal reflects: the same V·D over the mirrored hemisphere, directional albedo
// E(wo) of the GGX lobe — 1 for a smooth wall, which then passes the view straight through. Both by
// their own samplers; the wall's samples all go below. Its sampler (both hemispheres, a coloured
// wall with reflection) matches its density.
TEST(Transmission, ThinWallLetsThroughWhatAMetalReflects) {
  ShadingParams wall;
  wall.base_color = Rgb(1.0f);
  wall.specular = 0.0f;
  wall.transmission = 1.0f;
  ShadingParams metal;
  metal.base_color = Rgb(1.0f);
  metal.metallic = 1.0f;
  for (const float roughness : {0.0f, 0.3f, 0.7f}) {
    wall.roughness = metal.roughness = roughness;
    const SurfaceBsdf w(wall), m(metal);
    for (const double theta : {0.0, 50.0, 80.0}) {
      const glm::vec3 wo = direction_deg(theta, 10.0);
      double se_w = 0, se_m = 0;
      const double through = albedo(w, wo, 40000, 29, &se_w), reflected = albedo(m, wo, 40000, 31, &se_m);
      EXPECT_NEAR(through, reflected, 4 * std::hypot(se_w, se_m) + 1e-6) << roughness << " " << theta;
      if (roughness == 0.0f) {
        EXPECT_NEAR(through, 1.0, 1e-3) << theta;
      }
      const BsdfSample s = w.sample(wo, SampleU(0.5f, 0.3f, 0.6f));
      EXPECT_EQ(s.kind, SampleKind::finite);
      EXPECT_LT(s.wi.z, 0.0f);
      if (roughness == 0.0f) {
        EXPECT_NEAR(glm::length(s.wi + wo), 0.0, 1e-2) << "straight through";
      }
    }
  }
  ShadingParams p;
  p.base_color = Rgb(0.7f, 0.5f, 0.3f);
  p.roughness = 0.5f;
  p.transmission = 0.6f;
  expect_sampler_matches(SurfaceBsdf(p), {20.0, 70.0}, 0.0);
}

// KHR_materials_dispersion: the Cauchy index keeps the extension's defining property, n(486.1 nm) −
// n(656.3 nm) = (n_d − 1)/V_d with V_d = 20/dispersion (to 0.04 %: the text's constant 523655 rounds
// 1/(486.1⁻² − 656.3⁻²) = 523454), and n(587.6 nm) = n_d; the channels' indices rise from red to
// blue; never below 1.
TEST(Dispersion, CauchyIndexHasTheAbbeNumbersSpread) {
  for (const float ior : {1.33f, 1.5f, 2.4f})
    for (const float dispersion : {0.33f, 1.0f, 2.04f}) {
      const double vd = 20.0 / dispersion;
      EXPECT_NEAR(dispersion_ior(ior, dispersion, 486.1f) - dispersion_ior(ior, dispersion, 656.3f), (ior - 1) / vd,
                  6e-4 * (ior - 1) / vd + 1e-6);
      EXPECT_NEAR(dispersion_ior(ior, dispersion, 587.6f), ior, 1e-4);
      EXPECT_LT(dispersion_ior(ior, dispersion, kChannelWavelengthNm[0]),
                dispersion_ior(ior, dispersion, kChannelWavelengthNm[1]));
      EXPECT_LT(dispersion_ior(ior, dispersion, kChannelWavelengthNm[1]),
                dispersion_ior(ior, dispersion, kChannelWavelengthNm[2]));
    }
  EXPECT_EQ(dispersion_ior(1.5f, 0.0f, 400.0f), 1.5f);
  EXPECT_GE(dispersion_ior(1.01f, 1000.0f, 700.0f), 1.0f);
}

// KHR_materials_volume's refraction: Snell's direction with radiance scaled by (1 − F)/η² entering
// glass (η = 1.5), and, leaving it (η = 1/1.5) past the critical angle, no transmission: the
// specular lobe's Fresnel is 1 and reflects everything (a smooth white dielectric's albedo is its
// GGX lobe's, near 1).
TEST(Volume, RefractsByTheIorsRatioWithTotalInternalReflection) {
  ShadingParams p;
  p.base_color = Rgb(1.0f);
  p.roughness = 0.0f;
  p.transmission = 1.0f;
  p.thin_walled = false;
  p.eta = 1.5f;
  const glm::vec3 wo = direction_deg(45.0, 30.0);
  const Impulses in = SurfaceBsdf(p).impulses_in(wo);
  ASSERT_EQ(in.count, 1);
  const glm::vec3 wt = in.items[0].direction;
  const double sin_t = std::sin(kPiD / 4) / 1.5;
  EXPECT_NEAR(wt.z, -std::sqrt(1 - sin_t * sin_t), 1e-6);
  EXPECT_NEAR(std::atan2(wt.y, wt.x), std::atan2(-wo.y, -wo.x), 1e-6);  // the plane of incidence
  const double fr = 0.04 + 0.96 * std::pow(1 - std::cos(kPiD / 4), 5.0);
  EXPECT_NEAR(in.items[0].magnitude.x, (1 - fr) / 2.25, 1e-6);
  // Light leaving the same path backwards (impulses_out from below) crosses with the same magnitude.
  const Impulses out = SurfaceBsdf(p).impulses_out(wt);
  ASSERT_EQ(out.count, 1);
  EXPECT_NEAR(glm::length(out.items[0].direction - wo), 0.0, 1e-5);

  p.eta = 1.0f / 1.5f;  // inside, looking out
  const double critical = std::asin(1.0 / 1.5) * 180 / kPiD;  // 41.8°
  EXPECT_EQ(SurfaceBsdf(p).impulses_in(direction_deg(critical + 2, 0.0)).count, 0);
  EXPECT_EQ(SurfaceBsdf(p).impulses_in(direction_deg(critical - 2, 0.0)).count, 1);
  double se = 0;
  EXPECT_NEAR(albedo(SurfaceBsdf(p), direction_deg(60.0, 0.0), 20000, 17, &se), 1.0, 0.01);
}

}  // namespace
}  // namespace svbrdf
