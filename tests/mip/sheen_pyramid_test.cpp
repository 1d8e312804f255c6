// The sheen of the BRDF pyramid (mip/sheen_layer.h: each base lobe's sheen share, the texel's sheen
// means) against the exact reference of materials with a sheen, on the random family's sheen seeds
// (textures/random_material.h), with the spec's metrics and the directional albedo at every level ≥ 1;
// the mixture's sampler with a sheen; and what it stores.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <span>
#include <string>
#include <vector>

#include "appearance/rng.h"
#include "mip/direction_grid.h"
#include "mip/exact_reference.h"
#include "mip/lobe_mixture_bsdf.h"
#include "mip/metrics.h"
#include "mip/mip_data.h"
#include "mip/sheen_layer.h"
#include "tests/mip/level_figures.h"
#include "tests/mip/random_directions.h"
#include "tests/mip/sampling_check.h"
#include "textures/random_material.h"

namespace svbrdf {
namespace {

using testing_figures::Figures;
using testing_figures::measure;


// The first `n` seeds from `from` on whose draw has a sheen, textured or not as asked, and no
// anisotropy (the sheen against its sheenless twin alone; anisotropy_pyramid_test.cpp has the stretch).
std::vector<std::uint64_t> sheen_seeds(int n, std::uint64_t from, bool textured) {
  std::vector<std::uint64_t> out;
  for (std::uint64_t s = from; static_cast<int>(out.size()) < n; ++s) {
    const RandomMaterialDraw d = draw_random_material(s);
    if (d.sheen_color != glm::vec3(0.0f) && d.sheen_textured == textured && d.anisotropy == 0.0f) out.push_back(s);
  }
  return out;
}

// A seed's texels without its transmission: these figures are the sheen's (transmission_pyramid_test.cpp
// has the transmission), and the sampler's check holds the mixture's reflection.
MaterialTexels seed_texels(std::uint64_t seed, int size) {
  MaterialTexels m = random_material_texels(draw_random_material(seed), size);
  m.transmission_factor = 0.0f;
  m.transmission.clear();
  return m;
}

// A texel's mixture as the renderer's lookup makes it: its lobes, its radial correction, its sheen.
LobeMixtureBsdf mixture(const MipData& mip, int level, int i, int j, Lobe& scratch) {
  LobeMixtureBsdf b(brdf_texel(mip, level, i, j, scratch));
  b.set_correction(mip.brdf.correction(level, i, j), &mip.brdf.radial_grid());
  if (const SheenLayer* s = brdf_sheen(mip, level, i, j)) b.set_sheen(*s);
  return b;
}

// At level 0 the mixture of a texel's lobe under its sheen is the extension's layering (the exact
// reference's, sheen_layer.h sheen_terms, itself held to the extension's text in sheen_layer_test.cpp)
// to float precision, on random pairs over every texel of textured and untextured sheens.
TEST(SheenPyramid, Level0MixtureIsTheTexelsLayering) {
  for (const bool textured : {false, true}) {
    const std::uint64_t seed = sheen_seeds(1, 1, textured)[0];
    SCOPED_TRACE(draw_random_material(seed).summary());
    const MipData mip = build_mip(seed_texels(seed, 8));
    ASSERT_TRUE(mip.brdf.has_sheen());
    Rng rng(seed, 9);
    int sheened = 0;  // texels with a sheen (a textured one covers only part of the texture)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        Lobe scratch;
        const LobeMixtureBsdf b = mixture(mip, 0, i, j, scratch);
        sheened += b.has_sheen();
        for (int k = 0; k < 16; ++k) {
          const glm::dvec3 wi = testing_directions::random_above(rng), wo = testing_directions::random_above(rng);
          const glm::dvec3 want = level0_eval(mip.level0, mip.level0.index(i, j), pair_terms<double>(wi, wo));
          const glm::dvec3 got(b.eval(glm::vec3(wi), glm::vec3(wo)));
          for (int c = 0; c < 3; ++c) ASSERT_NEAR(got[c], want[c], 2e-4 * want[c] + 1e-6) << "texel " << i << "," << j;
        }
      }
    EXPECT_GT(sheened, 8);
  }
}

// A seed's figures at every level ≥ 1 against its sheenless twin's (the same base): the sheen may add
// at most `d_elog` to e_log, `d_emean` to e_mean and `d_albedo` to each albedo error — what the base's
// own reduction leaves is the base's to answer for. The budget: 2 B a base slot over the base's bytes.
void check(std::uint64_t seed, double d_elog, double d_emean, double d_albedo) {
  const MaterialTexels m = seed_texels(seed, 32);
  const MipData mip = build_mip(m);
  ASSERT_TRUE(mip.brdf.has_sheen());
  MaterialTexels bare = m;
  bare.sheen_color_factor = glm::vec3(0.0f);
  bare.sheen_color.clear();
  bare.sheen_roughness.clear();
  const MipData twin_mip = build_mip(bare);
  ASSERT_FALSE(twin_mip.brdf.has_sheen());
  const std::vector<Figures> sheen = measure(mip), twin = measure(twin_mip);
  for (std::size_t k = 0; k < sheen.size(); ++k) {
    const int level = int(k) + 1;
    const Figures &s = sheen[k], &t = twin[k];
    SCOPED_TRACE(draw_random_material(seed).summary() + ", level " + std::to_string(level));
    testing_figures::expect_within_twin(seed, level, s, t, mip.brdf.bytes_per_texel(level),
                                        twin_mip.brdf.bytes_per_texel(level), d_elog, d_emean, d_albedo);
    EXPECT_EQ(mip.brdf.sheen_bytes_per_texel(level), mip.brdf.level(level).slots * kBytesPerSheenShare);
    EXPECT_LE(mip.brdf.bytes_per_texel(level), twin_mip.brdf.bytes_per_texel(level) + 4 * kBytesPerSheenShare);
  }
}

// Two untextured and two textured sheens of the random family (the first such seeds from 1).
TEST(SheenPyramid, RandomSheensMeetTheBars) {
  for (const bool textured : {false, true})
    for (const std::uint64_t seed : sheen_seeds(2, 1, textured)) check(seed, 0.01, 0.02, 0.01);
}

// The sheen term alone (sheen_layer.h f_sheen,eff: Σ_k of each base lobe's sheen over its spread normals,
// times C̄/Σ_k w_k·σ_k) of a level's mean against the texture's exact mean sheen term (every level-0
// texel's sheen_terms about its own normal), over the metric's pairs as e_mean takes them, and its sum
// over the pairs. The seeds: the first four sheens from 1 over dents or bumps tilted 15° or more (the
// relief whose spread of normals is isotropic, as the lobes' horizons assume). The term at each lobe's
// mean normal times its two sides, taken so before, is 0.05–3.1 off from level 2 on these seeds (the
// Charlie V's 1/(n·wi·n·wo) toward grazing); over its spread it is 0.006–0.081 off and its sum within
// 1 %: the bars are 0.1 and 3 %.
TEST(SheenPyramid, TheSheenFollowsItsLobesSpreadNormals) {
  const DirectionGrid& g = DirectionGrid::get();
  int seeds = 0;
  for (std::uint64_t seed = 1; seeds < 4; ++seed) {
    const RandomMaterialDraw d = draw_random_material(seed);
    if (d.sheen_color == glm::vec3(0.0f) || !(d.relief == Relief::dents || d.relief == Relief::bumps) ||
        d.max_tilt_deg < 15.0f)
      continue;
    ++seeds;
    SCOPED_TRACE(d.summary());
    constexpr int kSize = 16;
    const MaterialTexels m = seed_texels(seed, kSize);
    const MipData mip = build_mip(m);
    BrdfTable exact = make_table();
    for (std::size_t k = 0; k < m.size(); ++k) {
      const SheenLayer layer = m.sheen_layer(k);
      for (int q = 0; q < DirectionGrid::kPairs; ++q) exact[std::size_t(q)] += sheen_terms(layer, glm::dvec3(m.normal[k]), g.pair_d(q)).f;
    }
    for (int level = 1; level < mip.levels(); ++level) {
      const Extent e = mip.extent(level);
      const double area = double(m.size()) / double(e.width * e.height);
      BrdfTable got = make_table();
      for (int j = 0; j < e.height; ++j)
        for (int i = 0; i < e.width; ++i) {
          const SheenLayer* sheen = brdf_sheen(mip, level, i, j);
          ASSERT_NE(sheen, nullptr);
          Lobe scratch;
          const std::span<const Lobe> lobes = brdf_texel(mip, level, i, j, scratch);
          double shares = 0;
          for (const Lobe& l : lobes) shares += double(l.weight) * l.sheen;
          if (!(shares > 0)) continue;
          const glm::dvec3 scale = area * glm::dvec3(sheen->color) / shares;
          for (const Lobe& l : lobes) {
            const LobeShape<float> s = lobe_shape<float>(l);
            for (int q = 0; q < DirectionGrid::kPairs; ++q) {
              float sides = 0;
              lobe_eval(l, s, g.pair_f(q), 1.0f, &sides);
              got[std::size_t(q)] += double(sheen_lobe_terms(l, s, g.pair_f(q), sides, sheen->roughness).sheen) * scale;
            }
          }
        }
      double err2 = 0, ref2 = 0, sum = 0, ref = 0;
      for (int q = 0; q < DirectionGrid::kPairs; ++q) {
        const double c = g.direction(DirectionGrid::wi_index(q)).z;
        for (int a = 0; a < 3; ++a) {
          const double x = got[std::size_t(q)][a] * c, y = exact[std::size_t(q)][a] * c;
          err2 += (x - y) * (x - y), ref2 += y * y, sum += x, ref += y;
        }
      }
      std::printf("seed %3llu level %d  sheen term e_rel %.4f  sum over the pairs %+.4f\n", (unsigned long long)seed, level,
                  std::sqrt(err2 / ref2), sum / ref - 1);
      EXPECT_LE(std::sqrt(err2 / ref2), 0.1) << "level " << level;
      EXPECT_NEAR(sum / ref, 1.0, 0.03) << "level " << level;
    }
  }
}

// A sheen that holds everywhere gives every base lobe its max(colour) as share and every coarse texel
// the sheen itself; a material without a sheen stores none.
TEST(SheenPyramid, UniformSheenKeepsItsMeans) {
  const std::uint64_t seed = sheen_seeds(1, 1, false)[0];
  const RandomMaterialDraw d = draw_random_material(seed);
  const MipData mip = build_mip(seed_texels(seed, 16));
  const float share = std::max(d.sheen_color.r, std::max(d.sheen_color.g, d.sheen_color.b));
  for (int level = 1; level < mip.levels(); ++level) {
    const Extent e = mip.extent(level);
    for (int j = 0; j < e.height; ++j)
      for (int i = 0; i < e.width; ++i) {
        const SheenLayer& s = mip.brdf.sheen(level, i, j);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.color[c], d.sheen_color[c], 1e-6f);
        EXPECT_NEAR(s.roughness, d.sheen_roughness, 1e-6f);
        for (const Lobe& l : mip.brdf.texel(level, i, j)) EXPECT_NEAR(l.sheen, share, 1e-3f * share);
      }
  }
  std::uint64_t plain = 1;
  while (draw_random_material(plain).sheen_color != glm::vec3(0.0f)) ++plain;
  const MipData none = build_mip(seed_texels(plain, 16));
  EXPECT_FALSE(none.brdf.has_sheen());
  EXPECT_EQ(none.brdf.sheen_bytes_per_texel(1), 0);
}

// The mixture's sampler with a sheen (sampling_check.h: χ² of sample() against pdf(), the weights, their
// mean against the quadrature of f·cosθ), for a level-0 texel and coarse texels of a textured sheen,
// over the first seed that draws one, whatever its base's roughness.
TEST(SheenPyramid, SamplingWithASheenMatchesItsPdfAndIntegral) {
  const std::uint64_t seed = sheen_seeds(1, 1, true).front();
  ASSERT_GT(seed, 0u);
  const MipData mip = build_mip(seed_texels(seed, 16));
  // The first texel with a sheen at levels 0, 2 and 3 (row-major from the last row: a textured
  // sheen covers part of the texture).
  std::vector<LobeMixtureBsdf> mixtures;
  for (const int level : {0, 2, 3}) {
    const Extent e = mip.extent(level);
    Lobe scratch;
    for (int t = e.width * e.height - 1; t >= 0; --t) {
      LobeMixtureBsdf b = mixture(mip, level, t % e.width, t / e.width, scratch);
      if (b.has_sheen()) {
        mixtures.push_back(b);
        break;
      }
    }
  }
  ASSERT_EQ(mixtures.size(), 3u);
  for (const LobeMixtureBsdf& bsdf : mixtures)
    testing_sampling::expect_sampling_matches_pdf_and_integral(bsdf, glm::normalize(glm::vec3(0.4f, -0.2f, 0.5f)));
}

}  // namespace
}  // namespace svbrdf
