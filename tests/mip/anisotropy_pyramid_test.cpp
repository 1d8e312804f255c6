// The anisotropy of the BRDF pyramid (mip/lobe.h "Stretched shapes", mip/slope_stretch.h: a merged
// lobe keeps its union's stretch): what a merge of stretched lobes keeps exactly; the specular flux the
// merges keep, against the quadrature of stretched lobes; the stored stretch's rounding; the mixture's
// sampler with stretched lobes; and the figures against the exact reference of the random family's
// anisotropic seeds (textures/random_material.h), with the spec's metrics and the directional albedo at
// every level ≥ 1, against the same materials without their anisotropy.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "appearance/rng.h"
#include "mip/albedo_table.h"
#include "mip/lobe_mixture_bsdf.h"
#include "mip/lobe_reduction.h"
#include "mip/mip_data.h"
#include "mip/mip_file_channels.h"
#include "mip/param_pyramid.h"
#include "mip/stored_lobe.h"
#include "tests/mip/level_figures.h"
#include "tests/mip/random_directions.h"
#include "tests/mip/sampling_check.h"
#include "textures/random_material.h"

namespace svbrdf {
namespace {

constexpr double kPi = 3.14159265358979323846;

using testing_figures::Figures;
using testing_figures::measure;

// A random level-0 lobe of KHR_materials_anisotropy: perceptual roughness in [0.05, 0.8], strength in
// [0.3, 1], any direction, its normal within 0.3 rad of z.
Lobe random_stretched_lobe(Rng& rng) {
  const float rough = 0.05f + 0.75f * rng.next_float(), strength = 0.3f + 0.7f * rng.next_float();
  const float psi = float(2 * kPi) * rng.next_float(), tilt = 0.3f * rng.next_float(), az = float(2 * kPi) * rng.next_float();
  const glm::vec3 n(std::sin(tilt) * std::cos(az), std::sin(tilt) * std::sin(az), std::cos(tilt));
  const glm::vec3 color(0.3f + 0.6f * rng.next_float(), 0.3f + 0.6f * rng.next_float(), 0.3f + 0.6f * rng.next_float());
  return lobe_from_texel(color, rng.next_float() < 0.5f ? 1.0f : 0.0f, rough, n, 1.0f, {},
                         {strength, glm::vec2(std::cos(psi), std::sin(psi))});
}

// Lobes of one shape, one normal and one stretch are one lobe: their merge keeps the stretch and the
// shape, and reflects their sum (the colours average linearly, lobe_reduction.h), within float rounding.
TEST(AnisotropyPyramid, AMergeOfLobesSharingAStretchAndANormalIsExact) {
  Rng rng(71, 1);
  for (int trial = 0; trial < 200; ++trial) {
    Lobe a = random_stretched_lobe(rng), b = a;
    a.weight = 0.2f + rng.next_float(), b.weight = 0.2f + rng.next_float();
    b.diffuse *= 0.5f, b.f0 = glm::min(glm::vec3(1.0f), b.f0 * 1.3f);
    const Lobe m = merge_lobes(a, b);
    ASSERT_NEAR(m.stretch, a.stretch, 1e-4 * a.stretch) << "trial " << trial;
    ASSERT_NEAR(std::abs(glm::dot(m.stretch_dir, a.stretch_dir)), 1.0, 1e-6) << "trial " << trial;
    ASSERT_NEAR(m.alpha2, a.alpha2, 1e-4 * a.alpha2) << "trial " << trial;
    for (int k = 0; k < 8; ++k) {
      const glm::dvec3 wi = testing_directions::random_above(rng), wo = testing_directions::random_above(rng);
      const PairTerms<double> p = pair_terms<double>(wi, wo);
      const glm::dvec3 want = lobe_eval<double>(a, p) + lobe_eval<double>(b, p), got = lobe_eval<double>(m, p);
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], want[c], 2e-4 * want[c] + 1e-7) << "trial " << trial;
    }
  }
}

// The stretched lobe's specular flux as the merges keep it (albedo_table.h, the power mean of its
// widths) against the quadrature of the stretched lobe itself, over θi 0°, 45°, 75° and 8 incident
// azimuths, relative to the same for the isotropic lobe of its α² (the table's own normalization
// cancels): within 1 % on random lobes. The geometric mean alone (the lobe's α²) misses by up to 68 %.
TEST(AnisotropyPyramid, TheFluxMergesKeepIsTheStretchedLobesOwn) {
  const auto quadrature = [](const Lobe& l) {
    double sum = 0;
    for (const double theta : {0.0, 45.0, 75.0})
      for (int az = 0; az < 8; ++az) {
        const double t = theta * kPi / 180, p = az * kPi / 8;
        const glm::dvec3 wi(std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t));
        sum += directional_albedo(std::span<const Lobe>(&l, 1), wi, 24).g;
      }
    return sum;
  };
  Rng rng(72, 1);
  for (int trial = 0; trial < 12; ++trial) {
    Lobe l = random_stretched_lobe(rng);
    l.normal = glm::vec3(0, 0, 1), l.diffuse = glm::vec3(0.0f), l.f0 = glm::vec3(1.0f);
    Lobe iso = l;
    iso.stretch = 1.0f;
    const double got = reduction::specular_flux(l) / reduction::specular_flux(iso);
    const double want = quadrature(l) / quadrature(iso);
    EXPECT_NEAR(got, want, 0.01 * want) << "trial " << trial << ": α² " << l.alpha2 << ", r " << l.stretch;
  }
}

// A stretch is stored once: rounding a rounded lobe changes nothing (the MIP file's round trip is
// exact); its direction keeps 3e-6 rad and ln r 5e-4 of itself; a stretch below 1.001 is none.
TEST(AnisotropyPyramid, TheStoredStretchRoundsOnce) {
  Rng rng(73, 1);
  for (int trial = 0; trial < 2000; ++trial) {
    Lobe l = random_stretched_lobe(rng);
    if (trial % 10 == 0) l.stretch = 1.0f + 0.002f * rng.next_float();
    Lobe once = l;
    round_to_stored(once);
    Lobe twice = once;
    round_to_stored(twice);
    ASSERT_EQ(std::memcmp(&once, &twice, sizeof once), 0) << "trial " << trial;
    if (l.stretch < 1.001f) {
      ASSERT_EQ(once.stretch, 1.0f) << "trial " << trial;
      continue;
    }
    ASSERT_NEAR(std::log(once.stretch), std::log(l.stretch), 5e-4 * std::log(l.stretch) + 1e-7) << "trial " << trial;
    const double cross = l.stretch_dir.x * once.stretch_dir.y - l.stretch_dir.y * once.stretch_dir.x;
    ASSERT_LT(std::abs(cross), 3e-6) << "trial " << trial;
  }
}

// A corrupt file's stretch codes (NaN, negative, past the half's range) read as some finite stretch
// and a unit direction, never an undefined conversion (mip_file_channels.h unpack_lobe).
TEST(AnisotropyPyramid, CorruptStretchCodesReadAsAFiniteStretch) {
  using mip_file_channels::Role;
  const float nan = std::nanf("");
  for (const float code : {nan, -3.0f, 0.5f, 65504.0f})
    for (const float dir : {nan, -7.0f, 5.0f, 4096.0f, 65504.0f}) {
      mip_file_channels::LobeValues v;
      v[Role::weight] = 1.0f, v[Role::alpha] = 0.3f, v[Role::shape] = -1.0f, v[Role::skirt] = 1.0f, v[Role::f90] = 1.0f;
      v[Role::stretch] = code, v[Role::stretch_dir_hi] = dir, v[Role::stretch_dir_lo] = dir;
      const Lobe l = mip_file_channels::unpack_lobe(v);
      EXPECT_TRUE(std::isfinite(l.stretch) && l.stretch >= 1.0f) << code << " " << dir;
      EXPECT_NEAR(glm::length(l.stretch_dir), 1.0f, 1e-6f) << code << " " << dir;
    }
}

// The mixture's sampler with stretched lobes (sampling_check.h: χ² of sample() against pdf(), the
// weights, their mean against the quadrature of f·cosθ): it proposes isotropic GGX about each lobe and
// weighs by the whole f, so stretched lobes change its variance, never its mean.
TEST(AnisotropyPyramid, SamplingStretchedLobesMatchesItsPdfAndIntegral) {
  std::uint64_t seed = 1;
  while (!draw_random_material(seed).anisotropy_textured) ++seed;
  const MipData mip = build_mip(random_material_texels(draw_random_material(seed), 16));
  for (const int level : {0, 2, 3}) {
    Lobe scratch;
    LobeMixtureBsdf b(brdf_texel(mip, level, 1, 1, scratch));
    if (const SheenLayer* s = brdf_sheen(mip, level, 1, 1)) b.set_sheen(*s);
    bool stretched = false;
    for (const Lobe& l : brdf_texel(mip, level, 1, 1, scratch)) stretched = stretched || l.stretch > 1.0f;
    ASSERT_TRUE(stretched) << "level " << level;
    testing_sampling::expect_sampling_matches_pdf_and_integral(b, glm::normalize(glm::vec3(0.4f, -0.2f, 0.5f)));
  }
}

// The parameter pyramid's anisotropy means (param_pyramid.h anisotropy_from_below) are axial: each
// child's strength s and angle φ average as s·(cos 2φ, sin 2φ). Children stretched across each other
// (φ and φ + 90°) cancel; φ and φ + 180° are one direction; a 2 × 2 of angles 10°, 30°, 10°, 30° at
// strengths 0.8, 0.4, 0.8, 0.4 is (0.8·(cos 20°, sin 20°) + 0.4·(cos 60°, sin 60°))/2 in doubled angles.
// The parameter filters shade the mean (param_lobes), whose stretch is that of a texel of it.
TEST(AnisotropyPyramid, TheParameterPyramidsMeanIsAxial) {
  const auto level1 = [](const std::array<float, 4>& deg, const std::array<float, 4>& strength) {
    MaterialTexels m(2, 2);
    m.anisotropy_factor = 1.0f;
    for (std::size_t k = 0; k < 4; ++k) {
      const float a = glm::radians(deg[k]);
      m.anisotropy.push_back(strength[k]);
      m.anisotropy_direction.push_back({std::cos(a), std::sin(a)});
    }
    const ParamPyramid p = ParamPyramid::build(m);
    EXPECT_TRUE(p.has_anisotropy());
    return *p.anisotropy(1, 0, 0);
  };
  EXPECT_NEAR(level1({0, 90, 0, 90}, {0.6f, 0.6f, 0.6f, 0.6f}).strength, 0.0f, 1e-6f);
  const AnisotropyLayer same = level1({20, 200, 20, 200}, {0.5f, 0.5f, 0.5f, 0.5f});
  EXPECT_NEAR(same.strength, 0.5f, 1e-6f);
  EXPECT_NEAR(std::abs(same.direction.x * std::sin(glm::radians(20.0f)) - same.direction.y * std::cos(glm::radians(20.0f))), 0.0f, 1e-6f);
  const AnisotropyLayer mixed = level1({10, 30, 10, 30}, {0.8f, 0.4f, 0.8f, 0.4f});
  const glm::dvec2 v = 0.5 * (0.8 * glm::dvec2(std::cos(kPi / 9), std::sin(kPi / 9)) + 0.4 * glm::dvec2(0.5, std::sqrt(0.75)));
  EXPECT_NEAR(mixed.strength, glm::length(v), 1e-6);
  EXPECT_NEAR(std::atan2(mixed.direction.y, mixed.direction.x), 0.5 * std::atan2(v.y, v.x), 1e-6);
  // The parameter filter's lobe of the mean is the level-0 lobe of a texel with those parameters.
  ParamTexel t{glm::vec3(0.7f), 1.0f, 0.3f, glm::vec3(0, 0, 1)};
  const Lobe want = lobe_from_texel(t.base_color, t.metallic, t.roughness, t.normal, 1.0f, {}, mixed);
  const Lobe got = param_lobes(t, TextureFilter::param, {}, nullptr, nullptr, &mixed).base;
  EXPECT_EQ(got.stretch, want.stretch);
  EXPECT_EQ(got.stretch_dir, want.stretch_dir);
  EXPECT_EQ(got.alpha2, want.alpha2);
  EXPECT_GT(got.stretch, 1.0f);
}

// The first `n` seeds from `from` on whose draw is anisotropic, textured or not as asked.
std::vector<std::uint64_t> anisotropic_seeds(int n, std::uint64_t from, bool textured) {
  std::vector<std::uint64_t> out;
  for (std::uint64_t s = from; static_cast<int>(out.size()) < n; ++s) {
    const RandomMaterialDraw d = draw_random_material(s);
    if (d.anisotropy > 0.0f && d.anisotropy_textured == textured) out.push_back(s);
  }
  return out;
}

// A seed's figures at every level ≥ 1 against its isotropic twin's (the same texels without their
// anisotropy): the stretch may add at most `d_elog` to e_log, `d_emean` to e_mean and `d_albedo` to
// each albedo error.
void check(std::uint64_t seed, int size, double d_elog, double d_emean, double d_albedo) {
  // Without the seed's transmission: these figures are the anisotropy's (transmission_pyramid_test.cpp
  // has the transmission).
  MaterialTexels m = random_material_texels(draw_random_material(seed), size);
  m.transmission_factor = 0.0f;
  m.transmission.clear();
  ASSERT_TRUE(m.has_anisotropy());
  const MipData mip = build_mip(m);
  MaterialTexels bare = m;
  bare.anisotropy_factor = 0.0f;
  bare.anisotropy.clear();
  bare.anisotropy_direction.clear();
  const MipData twin_mip = build_mip(bare);
  const std::vector<Figures> got = measure(mip), twin = measure(twin_mip);
  for (std::size_t k = 0; k < got.size(); ++k) {
    const int level = int(k) + 1;
    const Figures &s = got[k], &t = twin[k];
    SCOPED_TRACE(draw_random_material(seed).summary() + ", level " + std::to_string(level));
    testing_figures::expect_within_twin(seed, level, s, t, mip.brdf.bytes_per_texel(level),
                                        twin_mip.brdf.bytes_per_texel(level), d_elog, d_emean, d_albedo);
  }
}

// Two untextured and two textured anisotropies of the random family (the first such seeds from 1).
// The bars are what the reduction reaches on them, rounded up by about a third (docs/mip-algorithm.md,
// §8 sets them against the targets): the stretched shapes leave e_log within 0.08 of the twins', and
// the albedo within 5 % (the twins keep their radial correction from level 4 on, which stretched lobes
// do not take).
TEST(AnisotropyPyramid, RandomAnisotropiesAgainstTheirIsotropicTwins) {
  for (const bool textured : {false, true})
    for (const std::uint64_t seed : anisotropic_seeds(2, 1, textured)) check(seed, 32, 0.1, 2.5, 0.06);
}

}  // namespace
}  // namespace svbrdf
