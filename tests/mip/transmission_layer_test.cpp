// A thin-walled KHR_materials_transmission in the BRDF MIP's lobes (mip/lobe.h, "Transmission"): a
// level-0 lobe's transmission against the extension's BTDF transcribed in double and against the
// renderer's glTF surface BSDF (appearance/gltf_surface_bsdf.h), with and without the specular layer
// and the anisotropy; what the transmission leaves of the reflection; its factors under a tint; the
// texel mixture's sampler over both hemispheres (mip/lobe_mixture_bsdf.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "appearance/frame.h"
#include "appearance/gltf_surface_bsdf.h"
#include "appearance/rng.h"
#include "chi2.h"
#include "gltf_transcription.h"
#include "mip/albedo_table.h"
#include "mip/exact_reference.h"
#include "mip/lobe.h"
#include "mip/lobe_mixture_bsdf.h"
#include "mip/lobe_reduction.h"
#include "random_directions.h"

namespace svbrdf {
namespace {

using gltf_transcription::anisotropic_vd;
using gltf_transcription::kPi;
using testing_directions::random_above;

// A texel's parameters, each exactly a float.
struct Texel {
  glm::dvec3 base{0.5};
  double metallic = 0, roughness = 0.5, transmission = 0;
  glm::dvec3 normal{0, 0, 1};
  double specular = 1, ior = 1.5;  // KHR_materials_specular's factor, KHR_materials_ior
  glm::dvec3 specular_color{1.0};
  double strength = 0;  // KHR_materials_anisotropy
  glm::dvec2 dir{1, 0};
};

Texel random_texel(Rng& rng) {
  Texel t;
  t.base = {rng.next_float(), rng.next_float(), rng.next_float()};
  t.metallic = rng.next_float() < 0.5f ? 0.0f : rng.next_float();
  t.roughness = 0.2f + 0.8f * rng.next_float();
  t.transmission = rng.next_float() < 0.25f ? 1.0f : rng.next_float();
  const float tilt = 0.5f * rng.next_float(), phi = 6.2831853f * rng.next_float();
  t.normal = glm::dvec3(glm::vec3(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt)));
  if (rng.next_float() < 0.5f) {
    t.specular = rng.next_float();
    t.ior = 1.2f + rng.next_float();
    t.specular_color = {rng.next_float(), rng.next_float(), rng.next_float()};
  }
  if (rng.next_float() < 0.3f) {
    t.strength = rng.next_float();
    const float psi = 6.2831853f * rng.next_float();
    t.dir = glm::dvec2(glm::vec2(std::cos(psi), std::sin(psi)));
  }
  return t;
}

Lobe lobe_of(const Texel& t) {
  SpecularLayer layer;
  layer.specular = float(t.specular), layer.ior = float(t.ior), layer.color = glm::vec3(t.specular_color);
  return lobe_from_texel(glm::vec3(t.base), float(t.metallic), float(t.roughness), glm::vec3(t.normal), 1.0f, layer,
                         AnisotropyLayer{float(t.strength), glm::vec2(t.dir)}, float(t.transmission));
}

// The transmission's f_eff transcribed in double from the extension's "Transmission BTDF" in the frame
// of the texel's normal n: L' = wi − 2(n·wi)n (the text's V − 2(N·L)N + L is V + L'), the base's
// 1 − s·max(fr) at |wo·H_T|, (1 − m)·T·c the BTDF's colour; f_eff = f·|n·wi|/|wi.z|.
glm::dvec3 transmission_khr(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::dvec3 n = glm::normalize(t.normal);
  const double ci = glm::dot(n, wi), co = glm::dot(n, wo);
  if (wi.z >= 0 || wo.z <= 0 || ci >= 0 || co <= 0) return glm::dvec3(0);
  const glm::dvec3 l = wi - 2 * ci * n;
  const glm::dvec3 h = glm::normalize(wo + l);
  const double vd = anisotropic_vd(t.roughness, t.strength, t.dir, n, l, wo);
  const double w = std::pow(1 - std::abs(glm::dot(wo, h)), 5);
  const double q = (t.ior - 1) / (t.ior + 1);
  const glm::dvec3 f0 = glm::min(q * q * t.specular_color, glm::dvec3(1));
  const glm::dvec3 fr = f0 + (1.0 - f0) * w;
  const double base = 1 - t.specular * std::max({fr.r, fr.g, fr.b});
  return (1 - t.metallic) * t.transmission * base * vd * t.base * (-ci / -wi.z);
}

// The renderer's level-0 model in a frame about the texel's normal (the anisotropy direction expressed
// in it as render/surface.cpp does), f_eff = f·|n·wi|/|wi.z| for either side.
SurfaceBsdf surface_of(const Texel& t, Frame& f) {
  const glm::vec3 n = glm::normalize(glm::vec3(t.normal));
  f = Frame::from_normal(n);
  ShadingParams p;
  p.base_color = Rgb(t.base), p.metallic = float(t.metallic), p.roughness = float(t.roughness);
  p.transmission = float(t.transmission);
  p.specular = float(t.specular), p.ior = float(t.ior), p.specular_color = Rgb(t.specular_color);
  p.anisotropy = float(t.strength);
  const glm::vec3 local = f.to_local(glm::vec3(float(t.dir.x), float(t.dir.y), 0.0f));
  p.anisotropy_direction = glm::normalize(glm::vec2(local.x, local.y));
  return SurfaceBsdf(p);
}
glm::dvec3 f_eff_surface(const Texel& t, const glm::dvec3& wi, const glm::dvec3& wo) {
  Frame f;
  const SurfaceBsdf b = surface_of(t, f);
  const glm::vec3 n = f.n;
  const double ci = glm::dot(glm::dvec3(n), wi);
  if (wo.z <= 0 || glm::dot(glm::dvec3(n), wo) <= 0 || (wi.z < 0) != (ci < 0)) return glm::dvec3(0);
  return glm::dvec3(b.eval(f.to_local(glm::vec3(wi)), f.to_local(glm::vec3(wo)))) * std::abs(ci) / std::abs(wi.z);
}

// At level 0 a lobe's transmission is the extension's: to 1e-6 relative in double against the
// transcription; in float, and the renderer's BSDF, to 1e-4 (5e-4 below 1e-4, as the anisotropy's).
// Its reflection, with ρ and ρ90 less the transmitted share, is the renderer's too.
TEST(TransmissionLayer, Level0LobeIsTheExtensionsBtdf) {
  Rng rng(71, 1);
  int compared = 0, reflected = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Texel t = random_texel(rng);
    const Lobe l = lobe_of(t);
    ASSERT_TRUE(transmits(l) || t.metallic == 1.0);
    glm::dvec3 wi = random_above(rng), wo = random_above(rng);
    wi.z = -wi.z;
    const glm::dvec3 want = transmission_khr(t, wi, wo);
    const glm::dvec3 got = lobe_transmission_eval<double>(l, lobe_shape<double>(l), wi, wo);
    const glm::dvec3 in_float(lobe_transmission_eval<float>(l, lobe_shape<float>(l), glm::vec3(wi), glm::vec3(wo)));
    const glm::dvec3 model = f_eff_surface(t, wi, wo);
    for (int c = 0; c < 3; ++c) {
      if (want[c] == 0) {
        EXPECT_EQ(got[c], 0.0);
        EXPECT_EQ(model[c], 0.0);
        continue;
      }
      const double tolerance = want[c] < 1e-4 ? 5e-4 : 1e-4;
      EXPECT_NEAR(got[c], want[c], 1e-6 * want[c]) << trial;
      EXPECT_NEAR(in_float[c], want[c], tolerance * want[c]) << trial;
      EXPECT_NEAR(model[c], want[c], tolerance * want[c]) << trial;
      ++compared;
    }
    // The reflection of the same texel, against the renderer's.
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

// No transmission, no change: a lobe without one has zero factors and evaluates none, and its other
// factors are those of a texel made without the argument, bit for bit.
TEST(TransmissionLayer, NoTransmissionLeavesTheLobeAsItWas) {
  Rng rng(72, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Texel t = random_texel(rng);
    t.transmission = 0;
    const Lobe l = lobe_of(t);
    EXPECT_FALSE(transmits(l));
    SpecularLayer layer;
    layer.specular = float(t.specular), layer.ior = float(t.ior), layer.color = glm::vec3(t.specular_color);
    const Lobe before = lobe_from_texel(glm::vec3(t.base), float(t.metallic), float(t.roughness), glm::vec3(t.normal), 1.0f,
                                        layer, AnisotropyLayer{float(t.strength), glm::vec2(t.dir)});
    EXPECT_EQ(l.diffuse, before.diffuse);
    EXPECT_EQ(l.diffuse90, before.diffuse90);
    EXPECT_EQ(l.f0, before.f0);
    EXPECT_EQ(l.f90, before.f90);
    const glm::dvec3 wi(0.3, 0.1, -0.9), wo(0.0, 0.2, 0.95);
    EXPECT_EQ(lobe_transmission_eval<double>(l, lobe_shape<double>(l), glm::normalize(wi), glm::normalize(wo)), glm::dvec3(0));
  }
}

// A tint v of the base colour (lobe.h tinted) scales the transmission's factors as it scales ρ: the
// tinted lobe's factors are those of the texel with colour c·v.
TEST(TransmissionLayer, TintScalesTheTransmission) {
  Rng rng(73, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const Texel t = random_texel(rng);
    const glm::dvec3 v(rng.next_float(), rng.next_float(), rng.next_float());
    Texel tinted_texel = t;
    tinted_texel.base = glm::dvec3(glm::vec3(t.base) * glm::vec3(v));
    const Lobe a = tinted(lobe_of(t), glm::vec3(v)), b = lobe_of(tinted_texel);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(a.transmission[c], b.transmission[c], 1e-6f * (1.0f + b.transmission[c])) << trial;
      EXPECT_NEAR(a.transmission90[c], b.transmission90[c], 1e-6f * (1.0f + b.transmission90[c])) << trial;
      EXPECT_NEAR(a.diffuse[c], b.diffuse[c], 1e-6f * (1.0f + b.diffuse[c])) << trial;
    }
  }
}

// The direction at polar angle θ and azimuth φ (degrees) above the surface.
glm::vec3 direction(double theta, double phi) {
  const double t = theta * kPi / 180, p = phi * kPi / 180;
  return glm::vec3(glm::dvec3(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)));
}

// Directional albedo over each hemisphere, ∫ f·|cosθ| dωi, by a model's own sampler (f·|cosθ|/pdf a
// sample): unbiased for any sampler whose density covers f. `se` receives the standard errors.
glm::dvec2 albedos(const Bsdf& b, const glm::vec3& wo, int n, std::uint64_t seed, glm::dvec2& se) {
  Rng rng(seed, 3);
  glm::dvec2 sum(0), sum2(0);
  for (int k = 0; k < n; ++k) {
    const BsdfSample s = b.sample(wo, SampleU(rng.next_float(), rng.next_float(), rng.next_float()));
    if (s.kind != SampleKind::finite) continue;
    const double x = (double(s.weight.r) + s.weight.g + s.weight.b) / 3;
    const int side = s.wi.z < 0 ? 1 : 0;
    sum[side] += x, sum2[side] += x * x;
  }
  const glm::dvec2 mean = sum / double(n);
  se = glm::sqrt(glm::max(sum2 / double(n) - mean * mean, glm::dvec2(0)) / double(n));
  return mean;
}

// A mixture of transmitting lobes — four tilted lobes of different roughness, transmission and
// colour, one of them a roughness mixture, one transmitting through a band, one stretched — draws the density its pdf() gives over both
// hemispheres (the sphere's χ² test, which also checks that the density integrates to the probability
// of a finite sample).
TEST(TransmissionLayer, MixtureSamplerMatchesItsDensityOverBothHemispheres) {
  Rng rng(74, 1);
  std::vector<Lobe> lobes;
  for (int k = 0; k < 4; ++k) {
    Texel t = random_texel(rng);
    t.strength = k == 3 ? 0.7 : 0.0;
    Lobe l = lobe_of(t);
    l.weight = 0.25f;
    if (k == 1) l.alpha2_hi = 8.0f * l.alpha2, l.ggx = 0.6f;
    if (k == 2) {  // a transmitting band 30× wide
      l.transmission = glm::max(l.transmission, glm::vec3(0.5f, 0.4f, 0.3f));
      l.transmission_alpha2 = 0.01f, l.transmission_alpha2_hi = 0.3f;
    }
    lobes.push_back(l);
  }
  const LobeMixtureBsdf b(lobes);
  ASSERT_TRUE(b.has_transmission());
  for (const double theta : {10.0, 45.0, 75.0}) {
    const testing::Chi2Result r = testing::chi2_test(b, direction(theta, 30.0));
    EXPECT_GT(r.p_value, 1e-3) << "θo " << theta << ": worst bin " << r.worst;
  }
}

// A merge gives the union's transmission the members' amplitude-weighted tail and peak moments, A =
// E[α²] and P = E[1/α²] (lobe.h "Transmission"): for two lobes of one roughness a GGX of it, for lobes of
// different roughness (pairs 4× and 100× apart in α², and a merged band merged again) the log-uniform
// band whose L(l, h) = (h − l)/ln(h/l) and L/(l·h) are A and P, within 1e-5; its τ is the weighted mean
// scaled to keep the union's transmitted flux.
TEST(TransmissionLayer, AMergeKeepsTheUnionsTailAndPeak) {
  const auto lobe = [](float roughness, float t, float weight) {
    return lobe_from_texel(glm::vec3(0.8f, 0.5f, 0.3f), 0.0f, roughness, glm::vec3(0, 0, 1), weight, {}, {}, t);
  };
  // The moments of a transmission shape from its fields alone.
  const auto moments = [](const Lobe& l) {
    const double lo = l.transmission_alpha2, hi = l.transmission_alpha2_hi;
    if (!(hi > lo)) return glm::dvec2(lo, 1 / lo);
    const double L = (hi - lo) / std::log(hi / lo);
    return glm::dvec2(L, L / (lo * hi));
  };
  const auto amplitude = [](const Lobe& l) {
    return double(l.weight) * (double(l.transmission.r) + l.transmission.g + l.transmission.b);
  };
  const Lobe same = merge_lobes(lobe(0.4f, 0.9f, 0.5f), lobe(0.4f, 0.3f, 0.5f));
  EXPECT_EQ(same.transmission_alpha2_hi, 0.0f);
  EXPECT_NEAR(same.transmission_alpha2, std::pow(0.4, 4), 1e-6);
  const Lobe a = lobe(0.25f, 0.9f, 0.3f), b = lobe(0.35f, 0.5f, 0.7f), c = lobe(0.8f, 0.6f, 0.4f);
  const Lobe ab = merge_lobes(a, b);
  for (const auto& [x, y] : {std::pair{a, b}, std::pair{a, c}, std::pair{ab, c}}) {
    const Lobe m = merge_lobes(x, y);
    const double ax = amplitude(x), ay = amplitude(y);
    const glm::dvec2 want = (ax * moments(x) + ay * moments(y)) / (ax + ay);
    EXPECT_GT(m.transmission_alpha2_hi, m.transmission_alpha2);
    EXPECT_NEAR(moments(m).x, want.x, 1e-5 * want.x);
    EXPECT_NEAR(moments(m).y, want.y, 1e-5 * want.y);
    using reduction::transmission_flux;
    EXPECT_NEAR(transmission_flux(m), transmission_flux(x) + transmission_flux(y), 1e-4 * transmission_flux(m));
  }
}

// A merge's transmission takes its members' stretch (lobe.h "Transmission"), not the reflection's,
// which also holds the spread of the members' normals: two anisotropic lobes tilted ±20° across their
// stretch merge into a reflection stretched further and a transmission stretched as each member. Two
// lobes stretched by r along x and along y transmit, merged, through the mean of their slope matrices,
// α²·(r + 1/r)/2 on each axis: isotropic, with the tail moment A = α²·(r + 1/r)/2 and the peak 1/α².
TEST(TransmissionLayer, AMergeTakesTheMembersTransmissionStretchNotTheirNormalsSpread) {
  const auto lobe = [](const glm::vec3& n, const glm::vec2& dir) {
    return lobe_from_texel(glm::vec3(0.8f, 0.5f, 0.3f), 0.0f, 0.3f, n, 0.5f, {}, AnisotropyLayer{0.5f, dir}, 0.8f);
  };
  const float t = std::sin(0.349066f), c = std::cos(0.349066f);
  const Lobe a = lobe(glm::vec3(t, 0, c), glm::vec2(0, 1)), b = lobe(glm::vec3(-t, 0, c), glm::vec2(0, 1));
  ASSERT_GT(a.stretch, 1.5f);
  const Lobe tilted = merge_lobes(a, b);
  EXPECT_GT(std::abs(std::log(tilted.stretch) - std::log(a.stretch)), 0.5) << "the normals' spread across the stretch";
  EXPECT_NEAR(tilted.transmission_stretch, a.transmission_stretch, 1e-5 * a.transmission_stretch);
  EXPECT_NEAR(std::abs(tilted.transmission_stretch_dir.y), 1.0f, 1e-6f);
  EXPECT_NEAR(tilted.transmission_alpha2, a.transmission_alpha2, 1e-6 * a.transmission_alpha2);
  EXPECT_EQ(tilted.transmission_alpha2_hi, 0.0f);

  const Lobe x = lobe(glm::vec3(0, 0, 1), glm::vec2(1, 0)), y = lobe(glm::vec3(0, 0, 1), glm::vec2(0, 1));
  const Lobe crossed = merge_lobes(x, y);
  EXPECT_EQ(crossed.transmission_stretch, 1.0f);
  const double a2 = x.transmission_alpha2, r = x.transmission_stretch;
  const double lo = crossed.transmission_alpha2, hi = crossed.transmission_alpha2_hi;
  ASSERT_GT(hi, lo);
  const double L = (hi - lo) / std::log(hi / lo);
  EXPECT_NEAR(L, a2 * (r + 1 / r) / 2, 1e-5 * L);
  EXPECT_NEAR(L / (lo * hi), 1 / a2, 1e-5 / a2);
}

// A level-0 texel's mixture (one lobe) reflects and transmits what the renderer's surface BSDF does:
// its directional albedo over each hemisphere, each by its own sampler, within 4σ. The texel's normal
// is the geometric one (the surface's frame is then the lobes').
TEST(TransmissionLayer, Level0MixtureTransmitsWhatTheSurfaceTransmits) {
  Rng rng(75, 1);
  for (int trial = 0; trial < 6; ++trial) {
    Texel t = random_texel(rng);
    t.normal = glm::dvec3(0, 0, 1);
    const LobeMixtureBsdf mixture(std::vector<Lobe>{lobe_of(t)});
    Frame f;
    const SurfaceBsdf surface = surface_of(t, f);
    for (const double theta : {20.0, 70.0}) {
      const glm::vec3 wo = direction(theta, 40.0);
      glm::dvec2 se_m, se_s;
      const glm::dvec2 m = albedos(mixture, wo, 40000, 5, se_m), s = albedos(surface, wo, 40000, 6, se_s);
      for (int side = 0; side < 2; ++side)
        EXPECT_NEAR(m[side], s[side], 4 * std::hypot(se_m[side], se_s[side]) + 1e-6)
            << "trial " << trial << " θo " << theta << (side ? " transmitted" : " reflected");
      EXPECT_GT(m[1], 0.0) << trial;
    }
  }
}

// Under a clear coat and a sheen, a level-0 texel's transmission — the exact reference's, in double, and
// its mixture's, in float — is the renderer's surface BSDF's: the lobe's BTDF under the sheen's albedo
// scaling at the mirrored pair and the coat's 1 − c·Fc(wo) (to 1e-4, 5e-4 below 1e-4 as above). The
// texels' normals and coat normals are the geometric one, so the surface's frame is the lobes'.
TEST(TransmissionLayer, Level0UnderCoatAndSheenIsTheSurfaces) {
  Rng rng(76, 1);
  MaterialTexels m(4, 4);
  m.clearcoat_factor = 1.0f, m.clearcoat.resize(m.size()), m.clearcoat_roughness_factor = 1.0f;
  m.clearcoat_roughness.resize(m.size());
  m.sheen_color_factor = glm::vec3(1.0f), m.sheen_color.resize(m.size()), m.sheen_roughness_factor = 1.0f;
  m.sheen_roughness.resize(m.size());
  m.transmission_factor = 1.0f, m.transmission.resize(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) {
    m.base_color[k] = {rng.next_float(), rng.next_float(), rng.next_float()};
    m.metallic[k] = k % 3 == 0 ? 0.5f * rng.next_float() : 0.0f;
    m.roughness[k] = 0.2f + 0.8f * rng.next_float();
    m.clearcoat[k] = rng.next_float(), m.clearcoat_roughness[k] = 0.1f + 0.9f * rng.next_float();
    m.sheen_color[k] = {rng.next_float(), rng.next_float(), rng.next_float()};
    m.sheen_roughness[k] = 0.2f + 0.8f * rng.next_float();
    m.transmission[k] = k % 4 == 1 ? 0.0f : rng.next_float();
  }
  const ExactReference exact(m);
  int compared = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const int i = trial % 4, j = (trial / 4) % 4;
    const std::size_t k = m.index(i, j);
    ShadingParams p;
    p.base_color = Rgb(m.base_color[k]), p.metallic = m.metallic[k], p.roughness = m.roughness[k];
    p.transmission = m.transmission[k];
    p.clearcoat = m.clearcoat[k], p.clearcoat_roughness = m.clearcoat_roughness[k];
    p.sheen_color = Rgb(m.sheen_color[k]), p.sheen_roughness = m.sheen_roughness[k];
    const SurfaceBsdf surface(p);
    Lobe scratch;
    LobeMixtureBsdf mixture(std::vector<Lobe>{level0_lobe(m, k)}, level0_coat(m, k, scratch).lobes);
    mixture.set_sheen(m.sheen_layer(k));
    glm::dvec3 wi = random_above(rng), wo = random_above(rng);
    wi.z = -wi.z;
    const glm::dvec3 want(surface.eval(glm::vec3(wi), glm::vec3(wo)));
    const glm::dvec3 got = exact.eval(0, i, j, wi, wo);
    const glm::dvec3 in_float(mixture.eval(glm::vec3(wi), glm::vec3(wo)));
    for (int c = 0; c < 3; ++c) {
      if (want[c] == 0) {
        EXPECT_EQ(got[c], 0.0) << trial;
        EXPECT_EQ(in_float[c], 0.0) << trial;
        continue;
      }
      const double tolerance = want[c] < 1e-4 ? 5e-4 : 1e-4;
      EXPECT_NEAR(got[c], want[c], tolerance * want[c]) << trial;
      EXPECT_NEAR(in_float[c], want[c], tolerance * want[c]) << trial;
      ++compared;
    }
  }
  EXPECT_GT(compared, 6000);
}

}  // namespace
}  // namespace svbrdf
