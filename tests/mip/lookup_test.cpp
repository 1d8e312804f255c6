// The renderer's lookups: the trilinear/anisotropic filter, the stochastic selection of one texel
// (unbiased: its mean is the filter-weighted mean of the texels' BRDFs), the mixture's sampling, and
// the deterministic trilinear parameter lookup.
#include <gtest/gtest.h>

#include <array>

#include <cmath>

#include "appearance/rng.h"
#include "mip/mip_data.h"
#include "mip/mip_lookup.h"
#include "tests/mip/sampling_check.h"
#include "tests/mip/synthetic_materials.h"

namespace svbrdf {
namespace {

float total_weight(const FilterTaps& t) {
  float s = 0;
  for (int k = 0; k < t.count; ++k) s += t.taps[static_cast<std::size_t>(k)].weight;
  return s;
}

TEST(FilterTaps, LevelsProbesAndWeights) {
  const Extent e{64, 64};
  const int levels = level_count(e);
  // A footprint one level-0 texel wide: level 0, bilinear (≤ 4 taps).
  FilterTaps t = filter_taps(e, levels, {{0.3f, 0.7f}, {1.0f / 64, 0}, {0, 1.0f / 64}});
  EXPECT_FLOAT_EQ(t.level, 0.0f);
  EXPECT_LE(t.count, 4);
  EXPECT_NEAR(total_weight(t), 1.0f, 1e-6f);
  // Four texels wide: level 2 exactly; 6 wide: between 2 and 3 (trilinear, ≤ 8 taps).
  t = filter_taps(e, levels, {{0.3f, 0.7f}, {4.0f / 64, 0}, {0, 4.0f / 64}});
  EXPECT_NEAR(t.level, 2.0f, 1e-5f);
  t = filter_taps(e, levels, {{0.3f, 0.7f}, {6.0f / 64, 0}, {0, 6.0f / 64}});
  EXPECT_NEAR(t.level, std::log2(6.0f), 1e-5f);
  EXPECT_LE(t.count, 8);
  EXPECT_NEAR(total_weight(t), 1.0f, 1e-6f);
  // Anisotropic 4:1 → 4 probes at the minor axis's level; 20:1 → 8 probes at major/8.
  t = filter_taps(e, levels, {{0.5f, 0.5f}, {8.0f / 64, 0}, {0, 2.0f / 64}});
  EXPECT_EQ(t.probes, 4);
  EXPECT_NEAR(t.level, 1.0f, 1e-5f);
  t = filter_taps(e, levels, {{0.5f, 0.5f}, {0, 40.0f / 64}, {2.0f / 64, 0}});
  EXPECT_EQ(t.probes, 8);
  EXPECT_NEAR(t.level, std::log2(5.0f), 1e-5f);
  EXPECT_NEAR(total_weight(t), 1.0f, 1e-5f);
  // Huge footprints clamp to the last level; wrap-around uvs and NaN stay in range.
  for (const Footprint& f : {Footprint{{-3.2f, 7.9f}, {100, 0}, {0, 100}}, Footprint{{1e6f, -1e6f}, {0.01f, 0}, {0, 0.01f}},
                             Footprint{{NAN, 0.5f}, {INFINITY, 0}, {0, NAN}},
                             // finite axes whose length overflows a float (a footprint scale of 1e30):
                             // ∞/∞ once reached an int conversion
                             Footprint{{0.5f, 0.5f}, {3e38f, 3e38f}, {1e30f, 0}}, Footprint{{0.5f, 0.5f}, {1e30f, 0}, {3e38f, 3e38f}},
                             Footprint{{3e38f, -3e38f}, {1e30f, 1e30f}, {1e30f, -1e30f}}}) {
    t = filter_taps(e, levels, f);
    EXPECT_NEAR(total_weight(t), 1.0f, 1e-5f);
    for (int k = 0; k < t.count; ++k) {
      const FilterTap& tap = t.taps[static_cast<std::size_t>(k)];
      const Extent le = level_extent(e, tap.level);
      EXPECT_TRUE(tap.level >= 0 && tap.level < levels && tap.i >= 0 && tap.i < le.width && tap.j >= 0 && tap.j < le.height);
    }
  }
}

// Filtering after shading is unbiased: the mean of 10^5 selected texels' BRDFs equals the
// filter-weighted mean of the texels' BRDFs within 3 standard errors, per channel and direction pair.
// The same of a coated material (its coat lobes chosen with their texel).
TEST(LookupBrdf, StochasticSelectionIsUnbiased) {
  for (const MaterialTexels& m : {synthetic::tray(32), synthetic::orange_peel(32)}) {
    SCOPED_TRACE(m.has_coat() ? "coated" : "tray");
    const MipData mip = build_mip(m);
    const Footprint f{{0.43f, 0.61f}, {3.1f / 32, 1.0f / 32}, {-0.4f / 32, 0.9f / 32}};  // anisotropic, between levels
    const FilterTaps taps = filter_taps(mip.brdf.level0(), mip.brdf.levels(), f);
    ASSERT_GT(taps.count, 8);
    const std::array<std::pair<glm::vec3, glm::vec3>, 3> pairs{{
        {glm::normalize(glm::vec3(0.3f, 0.1f, 1)), glm::normalize(glm::vec3(-0.3f, -0.1f, 1))},  // near the highlight
        {glm::normalize(glm::vec3(0.5f, 0.0f, 1)), glm::normalize(glm::vec3(-0.2f, 0.3f, 1))},
        {glm::normalize(glm::vec3(0.9f, 0.2f, 0.3f)), glm::normalize(glm::vec3(0.1f, -0.8f, 0.5f))},
    }};
    for (const auto& [wi, wo] : pairs) {
      glm::dvec3 expected(0);
      for (int k = 0; k < taps.count; ++k) {
        const FilterTap& t = taps.taps[static_cast<std::size_t>(k)];
        Lobe scratch, coat;
        const LobeMixtureBsdf texel(brdf_texel(mip, t.level, t.i, t.j, scratch), brdf_coat(mip, t.level, t.i, t.j, coat).lobes);
        expected += double(t.weight) * glm::dvec3(texel.eval(wi, wo));
      }
      Rng rng(17, 3);
      constexpr int n = 100000;
      glm::dvec3 sum(0), sum2(0);
      for (int s = 0; s < n; ++s) {
        const glm::dvec3 v(lookup_brdf(mip, f, rng.next_float()).eval(wi, wo));
        sum += v;
        sum2 += v * v;
      }
      const glm::dvec3 mean = sum / double(n);
      for (int c = 0; c < 3; ++c) {
        const double se = std::sqrt(std::max(0.0, sum2[c] / n - mean[c] * mean[c]) / n);
        EXPECT_NEAR(mean[c], expected[c], 3 * se + 1e-9 * expected[c]) << "channel " << c;
      }
    }
  }
}

// A coated texel's mixture (its base lobes with their coat shares, its coat lobes, its radial
// correction) evaluates as texel_eval evaluates the texel — the evaluation the pyramid's metrics hold
// to the exact reference (coat_layer.h) — at every level, level 0's texels included.
TEST(LobeMixtureBsdf, ACoatedTexelEvaluatesAsThePyramidsTexel) {
  const MipData mip = build_mip(synthetic::orange_peel(16));
  const std::array<std::pair<glm::dvec3, glm::dvec3>, 4> pairs{{
      {glm::normalize(glm::dvec3(0.3, 0.1, 1)), glm::normalize(glm::dvec3(-0.3, -0.1, 1))},
      {glm::normalize(glm::dvec3(0.5, 0.0, 1)), glm::normalize(glm::dvec3(-0.2, 0.3, 1))},
      {glm::normalize(glm::dvec3(0.9, 0.2, 0.3)), glm::normalize(glm::dvec3(0.1, -0.8, 0.5))},
      {glm::normalize(glm::dvec3(-0.2, 0.1, 0.2)), glm::normalize(glm::dvec3(0.9, -0.1, 0.15))},  // grazing: the coat's Fresnel
  }};
  int coated = 0;
  for (int level = 0; level < mip.levels(); ++level)
    for (int j = 0; j < mip.extent(level).height; j += 3)
      for (int i = 0; i < mip.extent(level).width; i += 2) {
        Lobe scratch, coat_scratch;
        const CoatTexel coat = brdf_coat(mip, level, i, j, coat_scratch);
        coated += coat.present();
        LobeMixtureBsdf b(brdf_texel(mip, level, i, j, scratch), coat.lobes);
        EXPECT_EQ(b.coat_size(), static_cast<int>(coat.lobes.size()));
        b.set_correction(mip.brdf.correction(level, i, j), &mip.brdf.radial_grid());
        for (const auto& [wi, wo] : pairs) {
          const glm::dvec3 want = texel_eval(mip, TextureFilter::brdf, level, i, j, wi, wo);
          const glm::dvec3 got(b.eval(glm::vec3(wi), glm::vec3(wo)));
          for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(got[c], want[c], 1e-5 * want[c] + 1e-7) << "level " << level << " texel " << i << "," << j;
        }
      }
  EXPECT_GT(coated, 10);
}

// The mixture's sampler: pdf() is the density sample() draws from (χ² over 64 bins of the
// hemisphere), the weights are f·cosθ/pdf, and their mean is ∫ f·cosθ dωi by adaptive quadrature (sampling_check.h).
TEST(LobeMixtureBsdf, SamplingMatchesItsPdfAndIntegral) {
  // A coarse texel of the bumpy wall and one of the tray: spread lobes and a sharp one.
  const MipData wall = build_mip(synthetic::painted_wall(16));
  const MipData tray = build_mip(synthetic::tray(16));
  // A coated one (a patchy glossy coat with its own bumps, over the tray) at level 2, and a level-0
  // texel of it: the coat lobes sampled among the base's.
  const MipData peel = build_mip(synthetic::orange_peel(16));
  Lobe peel0, peel0_coat;
  const std::span<const Lobe> peel0_base = brdf_texel(peel, 0, 5, 3, peel0);
  const CoatTexel peel0_coat_lobes = brdf_coat(peel, 0, 5, 3, peel0_coat);
  // And roughness mixtures with atoms (lobe.h): one under a band, one under a second atom.
  std::array<Lobe, 2> atoms{lobe_from_texel(glm::vec3(0.9f), 1.0f, 0.08f, glm::normalize(glm::vec3(0.1f, 0.0f, 1.0f)), 0.5f),
                            lobe_from_texel(glm::vec3(0.5f), 0.5f, 0.1f, glm::normalize(glm::vec3(-0.1f, 0.1f, 1.0f)), 0.5f)};
  atoms[0].alpha2_hi = 0.2f, atoms[0].ggx = 0.3f;
  atoms[1].alpha2_hi = 0.05f, atoms[1].ggx = 0.5f, atoms[1].skirt = 0.0f;
  // And glossy metals at the smallest α (10⁻³): a GGX lobe, and one almost all Beckmann, whose peak
  // has no tails for a quadrature to notice it by (sampling_check.h).
  const Lobe glossy = lobe_from_texel(glm::vec3(0.8f), 1.0f, 0.02f, glm::normalize(glm::vec3(0.2f, -0.1f, 1.0f)));
  Lobe beckmann = lobe_from_texel(glm::vec3(0.8f), 1.0f, 0.02f, glm::normalize(glm::vec3(-0.15f, 0.1f, 1.0f)));
  beckmann.ggx = 0.001f;
  ASSERT_GT(peel.brdf.coat(2, 1, 2).lobes.size(), 0u);
  ASSERT_TRUE(peel0_coat_lobes.present());
  for (const LobeMixtureBsdf& bsdf : {LobeMixtureBsdf(wall.brdf.texel(2, 1, 2)), LobeMixtureBsdf(tray.brdf.texel(3, 0, 1)),
                                      LobeMixtureBsdf(std::span<const Lobe>(atoms)),
                                      LobeMixtureBsdf(peel.brdf.texel(2, 1, 2), peel.brdf.coat(2, 1, 2).lobes),
                                      LobeMixtureBsdf(peel0_base, peel0_coat_lobes.lobes),
                                      LobeMixtureBsdf(std::span<const Lobe>(&glossy, 1)),
                                      LobeMixtureBsdf(std::span<const Lobe>(&beckmann, 1))}) {
    ASSERT_GT(bsdf.size(), 0);
    testing_sampling::expect_sampling_matches_pdf_and_integral(bsdf, glm::normalize(glm::vec3(0.4f, -0.2f, 0.8f)));
  }
}

// The parameter lookup is deterministic trilinear filtering of the parameters, the normal summed
// unnormalized and normalized once.
TEST(LookupParam, TrilinearMeansOfTheParameters) {
  MaterialTexels m(2, 1);
  m.base_color = {glm::vec3(1, 0, 0), glm::vec3(0, 0, 1)};
  m.metallic = {0.0f, 1.0f};
  m.roughness = {0.2f, 0.6f};
  m.normal = {glm::normalize(glm::vec3(0.5f, 0, 1)), glm::normalize(glm::vec3(-0.5f, 0, 1))};
  const ParamPyramid p = ParamPyramid::build(m);
  // Halfway between the two texel centres at level 0 (tiny footprint): the plain average.
  const ParamTexel t = filter_params(p, {{0.5f, 0.5f}, {1e-4f, 0}, {0, 1e-4f}});
  EXPECT_NEAR(t.base_color.r, 0.5f, 1e-5f);
  EXPECT_NEAR(t.base_color.b, 0.5f, 1e-5f);
  EXPECT_NEAR(t.metallic, 0.5f, 1e-5f);
  EXPECT_NEAR(t.roughness, 0.4f, 1e-5f);
  EXPECT_NEAR(t.normal.x, 0.0f, 1e-6f);
  EXPECT_NEAR(t.normal.z, 1.0f / std::sqrt(1.25f), 1e-5f);  // unnormalized: the mean of two unit vectors
  const Lobe l = lookup_param(p, {{0.5f, 0.5f}, {1e-4f, 0}, {0, 1e-4f}});
  EXPECT_NEAR(glm::length(l.normal), 1.0f, 1e-6f);  // normalized once, for shading
  // Toksvig widens α from the shortened mean normal: α'² = α² + 2(1 − r)/r.
  const float r = 1.0f / std::sqrt(1.25f);
  const Lobe tk = lookup_param(p, {{0.5f, 0.5f}, {1e-4f, 0}, {0, 1e-4f}}, TextureFilter::toksvig);
  EXPECT_NEAR(tk.alpha2, std::pow(0.4f * 0.4f, 2.0f) + 2 * (1 - r) / r, 1e-5f);
}

}  // namespace
}  // namespace svbrdf
