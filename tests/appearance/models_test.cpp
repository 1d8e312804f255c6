// Each model against its formula in brdf-models.md, re-derived here in double precision from the
// spec's text (not from the code under test), plus the special cases the issue names.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "appearance/blinn_phong.h"
#include "appearance/conductor_mirror.h"
#include "appearance/dielectric.h"
#include "appearance/fresnel.h"
#include "appearance/gltf_bsdf.h"
#include "appearance/lafortune.h"
#include "appearance/lambert.h"
#include "appearance/microfacet.h"
#include "appearance/mirror.h"
#include "appearance/oren_nayar.h"
#include "appearance/phong.h"
#include "appearance/registry.h"
#include "appearance/rng.h"
#include "test_models.h"

namespace svbrdf::testing {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Random unit vectors in the upper hemisphere, fixed seed; a few exact ones first.
std::vector<glm::vec3> upper_directions(int n, std::uint64_t seed) {
  std::vector<glm::vec3> out = {{0, 0, 1}, direction_deg(45, 0), direction_deg(80, 123), direction_deg(89, 300)};
  Rng rng(seed, 7);
  while (static_cast<int>(out.size()) < n) {
    const float z = rng.next_float(), phi = 6.2831853f * rng.next_float();
    const float r = std::sqrt(1 - z * z);
    if (z > 1e-3f) out.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  return out;
}

void expect_rgb_near(const Rgb& a, const glm::dvec3& b, double rel, const std::string& what) {
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(a[c], b[c], rel * std::abs(b[c]) + 1e-7) << what << " channel " << c;
}

// The glTF 2.0 Appendix B BRDF exactly as brdf-models.md writes it, in double.
glm::dvec3 gltf_reference(glm::dvec3 base, double metallic, double roughness, glm::dvec3 wi, glm::dvec3 wo) {
  if (wi.z <= 0 || wo.z <= 0) return glm::dvec3(0);
  const double a = std::max(roughness * roughness, 1e-3), a2 = a * a;
  const glm::dvec3 h = glm::normalize(wi + wo);
  const double d = a2 / (kPiD * std::pow(h.z * h.z * (a2 - 1) + 1, 2));
  const double v = 1.0 / (2.0 * (wo.z * std::sqrt(a2 + (1 - a2) * wi.z * wi.z) + wi.z * std::sqrt(a2 + (1 - a2) * wo.z * wo.z)));
  const double s = v * d, w = std::pow(1 - std::abs(glm::dot(wo, h)), 5);
  const glm::dvec3 dielectric = glm::mix(base / kPiD, glm::dvec3(s), 0.04 + 0.96 * w);
  const glm::dvec3 metal = s * (base + (1.0 - base) * w);
  return glm::mix(dielectric, metal, metallic);
}

TEST(Gltf, DoneWhenValueAtNormalIncidence) {
  // wi = wo = n, base_color 0.5, roughness 0.5: α = 0.25, D = 1/(πα²), V = 1/4 (both sqrt terms
  // are 1), w = 0, F = 0.04, so f = 0.96·0.5/π + 0.04·V·D.
  const double alpha = 0.25, expected = 0.96 * 0.5 / kPiD + 0.04 * 0.25 / (kPiD * alpha * alpha);
  EXPECT_NEAR(expected, 0.2037183, 1e-7);
  const auto bsdf = make_model("gltf", {"base_color=0.5", "roughness=0.5"});
  const Rgb f = bsdf->eval({0, 0, 1}, {0, 0, 1});
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], expected, 1e-6);
}

TEST(Gltf, MatchesTheSpecFormulaEverywhere) {
  const auto dirs = upper_directions(40, 11);
  for (double metallic : {0.0, 0.3, 1.0})
    for (double roughness : {0.0, 0.1, 0.5, 1.0}) {
      GltfParams p;
      p.base_color = Rgb(0.9f, 0.5f, 0.1f);
      p.metallic = static_cast<float>(metallic);
      p.roughness = static_cast<float>(roughness);
      const GltfBsdf bsdf(p);
      for (const glm::vec3& wi : dirs)
        for (const glm::vec3& wo : dirs) {
          const glm::dvec3 ref = gltf_reference(glm::dvec3(p.base_color), metallic, roughness, wi, wo);
          expect_rgb_near(bsdf.eval(wi, wo), ref, 2e-4, "gltf");
          expect_rgb_near(gltf_eval(p, wi, wo), ref, 2e-4, "gltf_eval");
        }
      EXPECT_EQ(bsdf.eval({0, 0, -1}, {0, 0, 1}), Rgb(0)) << "below the horizon";
    }
}

TEST(Lambert, IsAlbedoOverPi) {
  const Lambert l(Rgb(0.2f, 0.5f, 0.9f));
  expect_rgb_near(l.eval(direction_deg(30, 40), direction_deg(70, 200)), glm::dvec3(0.2, 0.5, 0.9) / kPiD, 1e-6, "lambert");
  EXPECT_EQ(l.eval(direction_deg(30, 40), direction_deg(95, 200)), Rgb(0));
}

TEST(Phong, FormulaAndShininessMapping) {
  const auto dirs = upper_directions(30, 5);
  const Phong p(Rgb(0.3f), Rgb(0.6f), 100.0f);
  for (const glm::vec3& wi : dirs)
    for (const glm::vec3& wo : dirs) {
      const double c = -double(wi.x) * wo.x - double(wi.y) * wo.y + double(wi.z) * wo.z;  // r(wi)·wo
      const double lobe = c > 0 ? 0.6 * 102.0 / (2 * kPiD) * std::pow(c, 100.0) : 0.0;
      expect_rgb_near(p.eval(wi, wo), glm::dvec3(0.3 / kPiD + lobe), 1e-4, "phong");
    }
  // shininess = log10(exponent): 2 ↔ n = 100 for phong, 3 ↔ s = 1000 for blinn-phong.
  const auto by_shininess = make_model("phong", {"kd=0.3", "ks=0.6", "shininess=2"});
  const auto by_blinn = make_model("blinn-phong", {"kl=0.1", "kg=0.9", "shininess=3"});
  const BlinnPhong blinn(Rgb(0.1f), Rgb(0.9f), 1000.0f);
  for (const glm::vec3& wi : dirs)
    for (const glm::vec3& wo : dirs) {
      const Rgb a = by_shininess->eval(wi, wo), b = p.eval(wi, wo);
      EXPECT_NEAR(a.x, b.x, 1e-4 * b.x + 1e-7);
      const Rgb c = by_blinn->eval(wi, wo), d = blinn.eval(wi, wo);
      EXPECT_NEAR(c.x, d.x, 1e-4 * d.x + 1e-7);
    }
  EXPECT_FLOAT_EQ(exponent_from_shininess(0), 1.0f);
  EXPECT_FLOAT_EQ(exponent_from_shininess(6), 1e6f);
}

TEST(BlinnPhong, Formula) {
  const BlinnPhong b(Rgb(0.2f), Rgb(0.7f), 50.0f);
  for (const glm::vec3& wi : upper_directions(20, 9))
    for (const glm::vec3& wo : upper_directions(20, 10)) {
      const glm::dvec3 h = glm::normalize(glm::dvec3(wi) + glm::dvec3(wo));
      const double f = 0.2 / kPiD + 0.7 * 58.0 / (8 * kPiD) * std::pow(h.z, 50.0);
      expect_rgb_near(b.eval(wi, wo), glm::dvec3(f), 1e-4, "blinn-phong");
    }
}

TEST(Lafortune, PhongShapedLobeEqualsPhong) {
  // Cx = Cy = −1, Cz = 1: the lobe is (r(wi)·wo)^n; with weight ks (n+2)/(2π) it is Phong's.
  const float n = 30, ks = 0.6f;
  const Lafortune laf(Rgb(0.3f), {LafortuneLobe{{-1, -1, 1}, n, Rgb(ks * (n + 2) / (2 * 3.14159265f))}});
  const Phong phong(Rgb(0.3f), Rgb(ks), n);
  char lobe[96];
  const double w = 0.6 * 32 / (2 * kPiD);
  std::snprintf(lobe, sizeof lobe, "lobe=-1,-1,1,30,%.9g,%.9g,%.9g", w, w, w);
  const auto via_registry = make_model("lafortune", {"kd=0.3", lobe});
  for (const glm::vec3& wi : upper_directions(25, 3))
    for (const glm::vec3& wo : upper_directions(25, 4)) {
      const Rgb a = laf.eval(wi, wo), b = phong.eval(wi, wo), c = via_registry->eval(wi, wo);
      EXPECT_NEAR(a.x, b.x, 1e-4 * b.x + 1e-7);
      EXPECT_NEAR(c.x, b.x, 1e-4 * b.x + 1e-7);
    }
  // No lobe: the diffuse term alone.
  const auto plain = make_model("lafortune", {"kd=0.4"});
  EXPECT_NEAR(plain->eval(direction_deg(20, 0), direction_deg(50, 90)).x, 0.4 / kPiD, 1e-7);
}

TEST(OrenNayar, SigmaZeroIsLambertAndFormulaInAngles) {
  const OrenNayar zero(Rgb(0.6f), 0.0f);
  const Lambert lambert(Rgb(0.6f));
  const auto dirs = upper_directions(30, 21);
  for (const glm::vec3& wi : dirs)
    for (const glm::vec3& wo : dirs) EXPECT_NEAR(zero.eval(wi, wo).x, lambert.eval(wi, wo).x, 1e-7);
  // The spec's formula written with angles: θ = acos(z), φ = atan2(y, x).
  const double sigma = 0.4, s2 = sigma * sigma;
  const double A = 1 - 0.5 * s2 / (s2 + 0.33), B = 0.45 * s2 / (s2 + 0.09);
  const OrenNayar on(Rgb(0.6f), static_cast<float>(sigma));
  for (const glm::vec3& wi : dirs)
    for (const glm::vec3& wo : dirs) {
      const double ti = std::acos(double(wi.z)), to = std::acos(double(wo.z));
      const bool normal = (wi.x == 0 && wi.y == 0) || (wo.x == 0 && wo.y == 0);
      const double cdphi = normal ? 0.0 : std::cos(std::atan2(double(wi.y), double(wi.x)) - std::atan2(double(wo.y), double(wo.x)));
      const double f = 0.6 / kPiD * (A + B * std::max(0.0, cdphi) * std::sin(std::max(ti, to)) * std::tan(std::min(ti, to)));
      EXPECT_NEAR(on.eval(wi, wo).x, f, 2e-5 * f + 1e-7);
    }
}

// D is normalized (∫ D(h) cos θh dωh = 1) and Λ is the right Smith function for it: the visible
// projected area ∫ max(0, w·h) D(h) dωh equals (1 + Λ(w)) w.z. Both by quadrature in (θ, φ).
TEST(MicrofacetDistribution, NormalizedAndSmithConsistent) {
  for (MicrofacetType type : {MicrofacetType::ggx, MicrofacetType::beckmann})
    for (float alpha : {0.1f, 0.3f, 0.7f, 1.2f}) {
      const MicrofacetDistribution dist{type, alpha};
      const int nt = 4000, np = 64;
      // θh via the substitution t = tan θh / α-ish spacing: a plain midpoint rule in θ with many
      // points suffices for α ≥ 0.1.
      double norm = 0;
      for (int i = 0; i < nt; ++i) {
        const double t = (i + 0.5) / nt * kPiD / 2;
        const glm::vec3 h(static_cast<float>(std::sin(t)), 0.0f, static_cast<float>(std::cos(t)));
        norm += dist.d(h) * std::cos(t) * std::sin(t) * (kPiD / 2 / nt) * 2 * kPiD;
      }
      EXPECT_NEAR(norm, 1.0, 2e-3) << "alpha " << alpha;
      for (double theta_w : {0.0, 40.0, 75.0, 88.0}) {
        const glm::dvec3 w(glm::dvec3(direction_deg(theta_w, 0)));
        double proj = 0;
        for (int i = 0; i < nt; ++i) {
          const double t = (i + 0.5) / nt * kPiD / 2;
          for (int j = 0; j < np; ++j) {
            const double p = (j + 0.5) / np * 2 * kPiD;
            const glm::dvec3 h(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
            proj += std::max(0.0, glm::dot(w, h)) * dist.d(glm::vec3(h)) * std::sin(t);
          }
        }
        proj *= (kPiD / 2 / nt) * (2 * kPiD / np);
        EXPECT_NEAR(proj, (1 + dist.lambda(glm::vec3(w))) * w.z, 3e-3 * w.z + 1e-4)
            << (type == MicrofacetType::ggx ? "ggx" : "beckmann") << " alpha " << alpha << " θ " << theta_w;
      }
    }
}

TEST(Microfacet, FormulaAliasAndMetalPlastic) {
  // GGX, height-correlated Smith, Schlick, written out from the spec.
  const double alpha = 0.35, f0 = 0.1;
  const auto m = make_model("microfacet", {"alpha=0.35", "f0=0.1", "kd=0.2"});
  for (const glm::vec3& wi : upper_directions(20, 31))
    for (const glm::vec3& wo : upper_directions(20, 32)) {
      const glm::dvec3 i(wi), o(wo), h = glm::normalize(i + o);
      const double a2 = alpha * alpha;
      const double d = a2 / (kPiD * std::pow(h.z * h.z * (a2 - 1) + 1, 2));
      auto lambda = [&](const glm::dvec3& w) {
        const double t2 = (1 - w.z * w.z) / (w.z * w.z);
        return (-1 + std::sqrt(1 + a2 * t2)) / 2;
      };
      const double g = 1 / (1 + lambda(i) + lambda(o));
      const double f = f0 + (1 - f0) * std::pow(1 - glm::dot(i, h), 5);
      expect_rgb_near(m->eval(wi, wo), glm::dvec3(0.2 / kPiD + f * d * g / (4 * i.z * o.z)), 5e-4, "microfacet");
    }
  // cook-torrance = microfacet distribution=beckmann masking=vgroove.
  const auto ct = make_model("cook-torrance", {"alpha=0.2", "fresnel=dielectric", "ior=1.7"});
  const auto mf = make_model("microfacet", {"distribution=beckmann", "masking=vgroove", "alpha=0.2", "fresnel=dielectric", "ior=1.7"});
  for (const glm::vec3& wi : upper_directions(15, 41))
    for (const glm::vec3& wo : upper_directions(15, 42)) EXPECT_EQ(ct->eval(wi, wo), mf->eval(wi, wo));
  // metal_plastic: 0 = plastic (kd = color, f0 = 0.04), 1 = metal (kd = 0, f0 = color).
  const auto plastic = make_model("microfacet", {"metal_plastic=0", "color=0.7,0.2,0.1"});
  const auto plastic_ref = make_model("microfacet", {"kd=0.7,0.2,0.1", "f0=0.04"});
  const auto metal = make_model("microfacet", {"metal_plastic=1", "color=0.7,0.2,0.1"});
  const auto metal_ref = make_model("microfacet", {"f0=0.7,0.2,0.1"});
  for (const glm::vec3& wi : upper_directions(15, 51))
    for (const glm::vec3& wo : upper_directions(15, 52)) {
      EXPECT_EQ(plastic->eval(wi, wo), plastic_ref->eval(wi, wo));
      EXPECT_EQ(metal->eval(wi, wo), metal_ref->eval(wi, wo));
    }
}

TEST(ImpulseModels, MirrorConductorAndDielectric) {
  const glm::vec3 wo = direction_deg(50, 30);
  const Mirror mirror(Rgb(0.4f));
  const Impulses mi = mirror.impulses_in(wo);
  ASSERT_EQ(mi.count, 1);
  EXPECT_NEAR(glm::length(mi.items[0].direction - glm::vec3(-wo.x, -wo.y, wo.z)), 0, 1e-7);
  EXPECT_EQ(mi.items[0].magnitude, Rgb(0.4f));
  EXPECT_EQ(mirror.eval(wo, mi.items[0].direction), Rgb(0));

  const ConductorMirror gold;
  const Impulses ci = gold.impulses_in(wo);
  ASSERT_EQ(ci.count, 1);
  EXPECT_NEAR(ci.items[0].magnitude.x, fresnel_conductor(wo.z, 0.2f, 3.9f), 1e-7);

  // Dielectric from outside: Snell sinθt = sinθi / η, magnitudes F and (1 − F)/η².
  const float eta = 1.5f;
  const Dielectric glass(eta);
  const Impulses di = glass.impulses_in(wo);
  ASSERT_EQ(di.count, 2);
  const double ti = 50 * kPiD / 180, tt = std::asin(std::sin(ti) / eta);
  const double rs = std::sin(ti - tt) / std::sin(ti + tt), rp = std::tan(ti - tt) / std::tan(ti + tt);
  const double F = 0.5 * (rs * rs + rp * rp);
  EXPECT_NEAR(di.items[0].magnitude.x, F, 1e-6);
  const glm::vec3 t = di.items[1].direction;
  EXPECT_NEAR(t.z, -std::cos(tt), 1e-6);
  EXPECT_NEAR(std::hypot(t.x, t.y), std::sin(tt), 1e-6);
  EXPECT_LT(glm::dot(glm::vec2(t.x, t.y), glm::vec2(wo.x, wo.y)), 0) << "refracted to the far side of the normal";
  EXPECT_NEAR(di.items[1].magnitude.x, (1 - F) / (eta * eta), 1e-6);
  // impulses_out from the refracted direction leads back to wo with the same magnitude.
  const Impulses back = glass.impulses_out(t);
  ASSERT_EQ(back.count, 2);
  EXPECT_NEAR(glm::length(back.items[1].direction - wo), 0, 1e-5);
  EXPECT_NEAR(back.items[1].magnitude.x, di.items[1].magnitude.x, 1e-5);
  // From inside past the critical angle asin(1/1.5) = 41.8°: total internal reflection only.
  const glm::vec3 inside = -direction_deg(45, 10);
  const Impulses tir = glass.impulses_in(inside);
  ASSERT_EQ(tir.count, 1);
  EXPECT_EQ(tir.items[0].magnitude, Rgb(1.0f));
  EXPECT_EQ(glass.impulses_in(-direction_deg(40, 10)).count, 2) << "below the critical angle light gets out";
}

}  // namespace
}  // namespace svbrdf::testing
