// The diffuse transmission (KHR_materials_diffuse_transmission, mip/diffuse_transmission.h) in the BRDF
// pyramid and the texel mixture: level 1 (a texel's four children, each its own lobe) is the exact
// reference's mean below the surface; the coarser levels keep the union's transmitted flux, whose
// closed form per texel is the integral of a Lambertian BTDF over the far hemisphere; the mixture's
// sampler draws the density its pdf() gives over both hemispheres.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "appearance/rng.h"
#include "appearance/sampling.h"
#include "chi2.h"
#include "mip/diffuse_transmission.h"
#include "mip/lobe_mixture_bsdf.h"
#include "mip/mip_data.h"
#include "random_directions.h"
#include "tests/mip/diffuse_transmission_materials.h"
#include "textures/random_material.h"

namespace svbrdf {
namespace {

using testing_directions::random_above;
using testing_materials::diffusely_transmitting;

constexpr double kPi = 3.14159265358979323846;

// A texel of the pyramid as the renderer's mixture: its lobes under its coat and sheen (mip_data.h).
LobeMixtureBsdf texel_mixture(const MipData& mip, int level, int i, int j) {
  Lobe scratch;
  LobeMixtureBsdf b(mip.brdf.texel(level, i, j), brdf_coat(mip, level, i, j, scratch).lobes);
  if (const SheenLayer* sheen = brdf_sheen(mip, level, i, j)) b.set_sheen(*sheen);
  return b;
}

// Level 1 of the pyramid is its texels' four children, each its own lobe (at most four: no merge), so
// below the surface it is the exact reference's mean but for the file's rounding: the lobes' weight and
// τd as halves (2^-11 relative each; 4e-3 allowed) and their normals' code (at most 8.4e-5 rad off,
// stored_normal.h, allowed as the absolute error it makes at grazing wi), checked at random pairs of
// every texel (under the family's clear coat where it has one).
TEST(DiffuseTransmissionPyramid, Level1IsTheExactMean) {
  for (const std::uint64_t seed : {3u, 6u, 9u, 12u}) {
    BrdfBuildOptions options;
    options.reduction.tolerance = 0.0f;  // no merge below max_lobes (lobe_reduction.h)
    const MipData mip = build_mip(diffusely_transmitting(seed, 16, false), options);
    const ExactReference exact(mip.level0);
    Rng rng(seed, 13);
    int compared = 0;
    for (int j = 0; j < mip.extent(1).height; ++j)
      for (int i = 0; i < mip.extent(1).width; ++i) {
        const LobeMixtureBsdf mixture = texel_mixture(mip, 1, i, j);
        // Σ weight·max(τd, τd90)/π over the lobes: the BTDF's scale, which a normal's code error δ moves
        // by at most δ/|wi.z| (its clipped cosine moves by δ at most).
        glm::dvec3 amplitude(0);
        for (const Lobe& l : mip.brdf.texel(1, i, j))
          amplitude += double(l.weight) * glm::dvec3(glm::max(l.diffuse_transmission, l.diffuse_transmission90)) / kPi;
        for (int trial = 0; trial < 40; ++trial) {
          glm::dvec3 wi = random_above(rng);
          const glm::dvec3 wo = random_above(rng);
          wi.z = -wi.z;
          const glm::dvec3 want = exact.eval(1, i, j, wi, wo);
          const glm::dvec3 got(mixture.eval(glm::vec3(wi), glm::vec3(wo)));
          for (int c = 0; c < 3; ++c) {
            if (!(want[c] > 0)) continue;
            EXPECT_NEAR(got[c], want[c], 4e-3 * want[c] + 8.4e-5 * amplitude[c] / -wi.z)
                << "seed " << seed << " texel " << i << "," << j;
            ++compared;
          }
        }
      }
    std::printf("seed %llu: %d values compared\n", static_cast<unsigned long long>(seed), compared);
    EXPECT_GT(compared, 2000);
  }
}

// The flux a texel transmits diffusely toward wo, ∫ f_eff·|wi.z| dwi over the far hemisphere. Each
// level-0 texel's in closed form: its Lambertian BTDF f = τ(n·wo)/π (diffuse_transmission.h) times
// ∫_{wi.z < 0} max(0, −n·wi) dwi = π·(1 + n_z)/2 (the irradiance of a plane tilted by θ from a uniform
// hemisphere: π·(1 + cos θ)/2), so τ(n·wo)·(1 + n_z)/2 where n·wo > 0. A coarse texel's is the mean of
// its texels'.
glm::dvec3 texel_flux(const MaterialTexels& m, std::size_t k, const glm::dvec3& wo) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(m.normal[k]));
  const double co = glm::dot(n, wo);
  if (!(co > 0)) return glm::dvec3(0);
  const Lobe l = level0_lobe(m, k);
  const double w = std::pow(1 - co, 5);
  const glm::dvec3 t(l.diffuse_transmission), t90(l.diffuse_transmission90);
  return (t + (t90 - t) * w) * ((1 + n.z) / 2);
}

// The same of a texel's lobes, by a cosine-weighted 96 × 96 stratified quadrature of the far hemisphere
// (∫ g·|wi.z| dwi = π·E[g] over cosine-distributed wi).
glm::dvec3 lobes_flux(std::span<const Lobe> lobes, const glm::dvec3& wo) {
  constexpr int kN = 96;
  glm::dvec3 sum(0);
  for (const Lobe& l : lobes) {
    const LobeShape<double> s = lobe_shape<double>(l);
    for (int a = 0; a < kN; ++a)
      for (int b = 0; b < kN; ++b) {
        glm::dvec3 wi(sample_cosine_hemisphere(glm::vec2((a + 0.5f) / kN, (b + 0.5f) / kN)));
        wi.z = -wi.z;
        sum += lobe_diffuse_transmission_eval<double>(l, s, wi, wo);
      }
  }
  return sum * (3.14159265358979323846 / (kN * kN));
}

// Every level keeps the texels' diffusely transmitted flux: the mean of the closed forms over a coarse
// texel against its lobes' quadrature, toward wo straight up and 60° off, per channel where it is above
// 5 % of the texel's largest. Each merge keeps the union's flux under the closed form's law
// (diffuse_transmission_flux); what a merged lobe does not carry is the Schlick weight over its
// normals' spread (it takes w at the mean normal, diffuse_transmission.h) and the exact clipped cosines
// of its texels, which its Gaussian horizons stand for (lobe.h). Measured worst over these seeds: 2.2 %
// straight up, 5.7 % from 60° (level 2 of seed 6); held to 3 % and 6.5 %. Without the merges'
// flux-keeping scale of τd: 6.3 %; without τd divided by the merges' weight scaling: far off.
TEST(DiffuseTransmissionPyramid, CoarseLevelsKeepTheFlux) {
  double worst = 0;
  for (const std::uint64_t seed : {3u, 6u, 9u, 12u}) {
    const MipData mip = build_mip(diffusely_transmitting(seed, 16, false));
    for (const double theta : {0.0, 60.0}) {
      const double t = theta * 3.14159265358979323846 / 180;
      const glm::dvec3 wo(std::sin(t) * 0.6, std::sin(t) * 0.8, std::cos(t));
      for (int level = 1; level < mip.levels(); ++level) {
        const Extent e = mip.extent(level);
        for (int j = 0; j < e.height; ++j)
          for (int i = 0; i < e.width; ++i) {
            const Coverage c = coverage(mip.extent(0), level, i, j);
            glm::dvec3 want(0);
            for (int y = c.rows.begin; y < c.rows.end; ++y)
              for (int x = c.columns.begin; x < c.columns.end; ++x) want += texel_flux(mip.level0, mip.level0.index(x, y), wo);
            want /= double(c.count());
            const glm::dvec3 got = lobes_flux(mip.brdf.texel(level, i, j), wo);
            const double m = std::max({want.r, want.g, want.b});
            for (int ch = 0; ch < 3; ++ch) {
              if (!(want[ch] > 0.05 * m)) continue;
              const double rel = std::abs(got[ch] / want[ch] - 1);
              worst = std::max(worst, rel);
              EXPECT_LT(rel, theta == 0.0 ? 0.03 : 0.065) << "seed " << seed << " θo " << theta << " level " << level << " texel " << i << ","
                                   << j << " channel " << ch;
            }
          }
      }
    }
  }
  std::printf("worst relative flux error %.5f\n", worst);
}

// A mixture of lobes that transmit diffusely — tilted, one spread (its normal's length 0.9), one also
// through a thin wall, one without a diffuse part — draws the density its pdf() gives over both
// hemispheres (the sphere's χ² test, which also checks that the density integrates to the probability
// of a finite sample).
TEST(DiffuseTransmissionPyramid, MixtureSamplerMatchesItsDensityOverBothHemispheres) {
  Rng rng(85, 1);
  std::vector<Lobe> lobes;
  for (int k = 0; k < 4; ++k) {
    const float tilt = 0.5f * rng.next_float(), phi = 6.2831853f * rng.next_float();
    const glm::vec3 n(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt));
    const glm::vec3 base(rng.next_float(), rng.next_float(), rng.next_float());
    const float transmission = k == 2 ? 0.6f : 0.0f;
    Lobe l = lobe_from_texel(base, 0.0f, 0.3f + 0.6f * rng.next_float(), n, 0.25f, {}, {}, transmission);
    add_diffuse_transmission(l, 0.0f, {}, transmission,
                             DiffuseTransmissionLayer{k == 3 ? 1.0f : 0.3f + 0.6f * rng.next_float(),
                                                      glm::vec3(rng.next_float(), rng.next_float(), rng.next_float())});
    if (k == 1) l.normal *= 0.9f;
    lobes.push_back(l);
  }
  const LobeMixtureBsdf b(lobes);
  ASSERT_TRUE(b.has_transmission());
  for (const double theta : {10.0, 45.0, 75.0}) {
    const double t = theta * 3.14159265358979323846 / 180;
    const glm::vec3 wo(glm::dvec3(std::sin(t) * std::cos(0.5), std::sin(t) * std::sin(0.5), std::cos(t)));
    const testing::Chi2Result r = testing::chi2_test(b, wo);
    EXPECT_GT(r.p_value, 1e-3) << "θo " << theta << ": worst bin " << r.worst;
  }
}

}  // namespace
}  // namespace svbrdf
