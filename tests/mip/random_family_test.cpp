// The BRDF pyramid over the random material family (textures/random_material.h): the glint regime's
// classification and the distribution over seeds on constructed inputs, then the figures of
// docs/mip-algorithm.md §8 ("The random family") on a few seeds at 64² (the default suite) and on 100
// seeds (ctest label `long`).
#include <gtest/gtest.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>

#include "apps/random_family_summary.h"
#include "base/json.h"
#include "tests/common/run_command.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

constexpr double kDeg = 3.14159265358979323846 / 180.0;

// 4 × 4 texels of one roughness, normals tilted alternately by ±tilt about the x axis; level 2's one
// texel covers them all.
MaterialTexels checker(float roughness, double tilt_deg) {
  MaterialTexels m(4, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const double a = ((i + j) % 2 ? 1 : -1) * tilt_deg * kDeg;
      m.roughness[m.index(i, j)] = roughness;
      m.normal[m.index(i, j)] = glm::vec3(0.0f, float(std::sin(a)), float(std::cos(a)));
    }
  return m;
}

// The regime needs at least two glossy texels (r < 0.3) whose normals spread (RMS angle about their
// mean) by at least their RMS α: r = 0.1 is α = 0.01 = 0.57°, r = 0.29 is α = 0.084 = 4.8°.
TEST(GlintRegime, GlossyTexelsWithNormalsSpreadBeyondTheirLobes) {
  EXPECT_FALSE(in_glint_regime(checker(0.1f, 0.0), 2, 0, 0));   // flat
  EXPECT_TRUE(in_glint_regime(checker(0.1f, 5.0), 2, 0, 0));    // 5° ≫ 0.57°
  EXPECT_TRUE(in_glint_regime(checker(0.1f, 0.6), 2, 0, 0));    // 0.6° ≥ 0.57°
  EXPECT_FALSE(in_glint_regime(checker(0.1f, 0.5), 2, 0, 0));   // 0.5° < 0.57°
  EXPECT_FALSE(in_glint_regime(checker(0.29f, 3.0), 2, 0, 0));  // 3° < 4.8°
  EXPECT_TRUE(in_glint_regime(checker(0.29f, 6.0), 2, 0, 0));
  EXPECT_FALSE(in_glint_regime(checker(0.5f, 20.0), 2, 0, 0));  // not glossy
  // One glossy texel among rough ones: a single spike, which one lobe holds.
  MaterialTexels one = checker(0.5f, 10.0);
  one.roughness[0] = 0.05f;
  EXPECT_FALSE(in_glint_regime(one, 2, 0, 0));
  one.roughness[1] = 0.05f;  // two, tilted 20° apart
  EXPECT_TRUE(in_glint_regime(one, 2, 0, 0));
  // Level 1: each 2 × 2 block on its own.
  EXPECT_FALSE(in_glint_regime(one, 1, 1, 1));
  EXPECT_TRUE(in_glint_regime(one, 1, 0, 0));
}

// Seeds 101–110 with level-1 e_log k/500 (k = 1..10), one more without a figure (NaN): median 5.5/500,
// 90th percentile (linear between order statistics: position 0.9·9 = 8.1) 9.1/500, max 10/500 at seed
// 110, and k ≤ 5 meet the target 0.01.
TEST(FamilySummary, DistributionOverSeeds) {
  std::vector<SeedFigures> seeds;
  for (int k = 10; k >= 0; --k) {
    SeedFigures s;
    s.seed = 100 + std::uint64_t(k);
    LevelFigures l;
    l.level = 1;
    l.brdf.elog_mean = k == 0 ? std::numeric_limits<double>::quiet_NaN() : k / 500.0;
    l.param.elog_mean = 1.0;
    s.levels.push_back(l);
    seeds.push_back(s);
  }
  const FamilyMetric& elog = family_metrics()[0];
  ASSERT_STREQ(elog.name, "e_log");
  const Distribution d = distribution(seeds, 1, elog, true);
  EXPECT_EQ(d.count, 10);
  EXPECT_NEAR(d.median, 5.5 / 500, 1e-15);
  EXPECT_NEAR(d.p90, 9.1 / 500, 1e-15);
  EXPECT_EQ(d.max, 10 / 500.0);
  EXPECT_EQ(d.worst_seed, 110u);
  EXPECT_EQ(d.meeting, 5);
  EXPECT_EQ(distribution(seeds, 1, elog, false).meeting, 0);
  EXPECT_EQ(distribution(seeds, 2, elog, true).count, 0);
}

// The bars one seed meets at every level ≥ 1: the targets of docs/mip-algorithm.md §8 where the seed
// meets them, else the figure it reaches (rounded up by about a third), which §8 sets against the
// target. `contrast`: brdf's e_log at most param's divided by it (0: not asserted).
struct SeedBars {
  std::uint64_t seed;
  double elog, emean, erel_other, albedo;
  double contrast;
};

// A seed that transmits carries its transmission as well as its reflection, to the margins of
// TransmissionPyramid (transmission_pyramid_test.cpp): e_log within the reflection's + 0.01, the flux
// over the pairs within its + 3 points.
void expect_transmission_carried(const TransmissionFigures& t) {
  ASSERT_GT(t.exact_transmitted, 0.0);
  EXPECT_LE(t.elog_transmitted, t.elog_reflected + 0.01);
  EXPECT_LE(std::abs(t.flux_transmitted), std::abs(t.flux_reflected) + 0.03);
}

void check_seed(const SeedBars& bars) {
  const SeedFigures f = measure_random_seed(bars.seed, 64);
  ASSERT_EQ(f.levels.size(), 6u);
  const bool transmits = draw_random_material(bars.seed).transmission > 0.0f;
  for (const LevelFigures& l : f.levels) {
    SCOPED_TRACE(f.summary + ", level " + std::to_string(l.level));
    const ModeFigures& b = l.brdf;
    // Level 1 holds the union of its four texels' lobes (K = 4) up to what the file stores.
    EXPECT_LE(b.elog_mean, l.level == 1 ? 1e-3 : bars.elog);
    EXPECT_LE(b.emean, bars.emean);
    if (!std::isnan(b.erel_mean_other)) {
      EXPECT_LE(b.erel_mean_other, bars.erel_other);
    }
    for (std::size_t a = 0; a < 3; ++a) {
      EXPECT_LE(std::abs(b.albedo_total[a]), bars.albedo) << "θi " << kAlbedoThetaDeg[a];
      EXPECT_LE(b.albedo_texel[a], bars.albedo) << "θi " << kAlbedoThetaDeg[a];
    }
    if (bars.contrast > 0) {
      EXPECT_LE(b.elog_mean, l.param.elog_mean / bars.contrast);
    }
    ASSERT_EQ(l.transmits, transmits);
    if (transmits) expect_transmission_carried(l.transmission);
  }
}

// One seed of each regime (bench/results/mip.md, "The random family"): a flat mixture of metal and
// paint with ±13 % roughness and a weak anisotropy (0.35; meets every target); a rough metal with 9°
// dents (e_mean and albedo 0.7 % at level 6); a rough anisotropic metal (0.62) with 28° dents (the
// horizon: albedo +5 % head-on; e_mean 0.044 and e_rel 0.047 at level 5, where the stretched lobes'
// merges add to the dents'; its paint, 28 % of the texels, transmits 0.42: transmitted e_log 0.0001 and
// flux +1.3 % at level 6, against the reflection's 0.004 and +3.3 % on the same pairs; param, whose lobes
// carry the mean transmission, comes to 2.0× brdf's e_log there, 0.0080 against 0.0040); a glossy ribbed metal (α = 0.005, 18° ribs along one axis: spikes that
// isotropic lobes cannot place, e_log 0.33 from level 3, 3.4× better than param); a glossy metal whose
// strong anisotropy (0.98) swirls by ±42° over 21 texels (e_log 0.09 at level 6, half param's; e_mean
// 1.3; albedo −5 % at 75°).
TEST(RandomFamily, FiveSeedsAt64MeetTheirBars) {
  for (const SeedBars& b : {SeedBars{17, 0.01, 0.013, 0.02, 0.005, 10}, SeedBars{19, 0.01, 0.01, 0.02, 0.01, 2},
                            SeedBars{14, 0.01, 0.1, 0.13, 0.1, 1.5}, SeedBars{18, 0.4, 1.0, 0.02, 0.05, 2},
                            SeedBars{9, 0.12, 1.7, 0.23, 0.07, 1.5}})
    check_seed(b);
}

// 100 seeds at 64² (ctest label `long`, SVBRDF_LONG=1): level 1 is near exact for every seed (its
// albedo within 0.2 %, or within 0.6 % for an anisotropic seed, whose merged stretched lobes keep their
// members' flux to the 0.6 % of the power mean of their widths, docs/mip-algorithm.md §4.5); flat
// seeds meet the targets but e_mean; over the seeds, brdf's median e_log is a third of param's or
// less and its median e_mean a tenth, and most seeds outside the glint regime meet the e_log target; the
// transmitting seeds carry their transmission as well as their reflection at the median (the margins
// above; seed 6, rough, brushed 34° and anisotropic, is past the flux margin at level 6, +19 % against
// +12.5 %: that sum over the pairs is mostly the straight-through peak, and its directional
// transmittance is +2.4 % head-on, docs/mip-algorithm.md §4.6).
TEST(RandomFamilyLong, HundredSeedsAt64) {
  if (!std::getenv("SVBRDF_LONG")) GTEST_SKIP() << "set SVBRDF_LONG=1 (ctest -L long)";
  constexpr int kSeeds = 100;
  std::vector<SeedFigures> seeds(kSeeds);
  tbb::parallel_for(0, kSeeds, [&](int k) { seeds[std::size_t(k)] = measure_random_seed(std::uint64_t(k) + 1, 64); });
  for (const SeedFigures& f : seeds) {
    const bool flat = draw_random_material(f.seed).relief == Relief::flat;
    for (const LevelFigures& l : f.levels) {
      SCOPED_TRACE(f.summary + ", level " + std::to_string(l.level));
      const ModeFigures& b = l.brdf;
      if (l.level == 1) {
        EXPECT_LE(b.elog_mean, 1e-3);
        if (!std::isnan(b.erel_mean_other)) {
          EXPECT_LE(b.erel_mean_other, 0.02);
        }
        const double albedo = draw_random_material(f.seed).anisotropy > 0.0f ? 6e-3 : 2e-3;
        for (std::size_t a = 0; a < 3; ++a) EXPECT_LE(std::abs(b.albedo_total[a]), albedo);
      }
      if (flat) {
        EXPECT_LE(b.elog_mean, 0.01);
        EXPECT_LE(b.emean, 0.015);
        for (std::size_t a = 0; a < 3; ++a) EXPECT_LE(std::abs(b.albedo_total[a]), 0.005);
      }
      EXPECT_EQ(l.transmits, draw_random_material(f.seed).transmission > 0.0f);
    }
  }
  const FamilyMetric& elog = family_metrics()[0];
  const FamilyMetric& emean = family_metrics()[1];
  for (int level = 2; level <= 6; ++level) {
    SCOPED_TRACE("level " + std::to_string(level));
    EXPECT_LE(distribution(seeds, level, elog, true).median, distribution(seeds, level, elog, false).median / 3);
    EXPECT_LE(distribution(seeds, level, emean, true).median, distribution(seeds, level, emean, false).median / 10);
    const Distribution calm = distribution(seeds, level, elog, true, true);
    EXPECT_GE(calm.meeting, 0.8 * calm.count);
    // The transmitting seeds' transmission at the median, to the margins of expect_transmission_carried.
    const std::vector<TransmissionMetric>& t = transmission_metrics();
    ASSERT_STREQ(t[0].name, "e_log, transmitted");
    ASSERT_STREQ(t[3].name, "|flux|, reflected");
    EXPECT_LE(distribution(seeds, level, t[0]).median, distribution(seeds, level, t[1]).median + 0.01);
    EXPECT_LE(distribution(seeds, level, t[2]).median, distribution(seeds, level, t[3]).median + 0.03);
  }
}

// svbrdf-bake random-family end to end: the table names each seed's draw, the JSON holds what the
// library measures (a transmitting seed's transmission included), and bad input is one line and exit 2.
TEST(RandomFamilyCli, ReportsWhatTheLibraryMeasures) {
  const testing::TempDir dir;
  const auto bake = [&](const std::string& args) {
    return testing::run_command(std::string("'") + SVBRDF_BAKE + "' random-family " + args, dir.path(), "");
  };
  const std::filesystem::path json = dir.path() / "out.json";
  const testing::CommandResult ok = bake("--seeds 2 --first-seed 5 --size 8 --threads 1 --json '" + json.string() + "'");
  ASSERT_EQ(ok.status, 0) << ok.err;
  EXPECT_NE(ok.out.find("The random family at 8x8, 2 seeds"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find(draw_random_material(5).summary()), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find(draw_random_material(6).summary()), std::string::npos) << ok.out;
  const Json j = Json::parse(testing::slurp(json));
  ASSERT_EQ(j["seeds"].size(), 2u);
  const SeedFigures f = measure_random_seed(6, 8);
  const Json& level = j["seeds"][1]["levels"][1];
  EXPECT_EQ(level["level"].get<int>(), 2);
  EXPECT_NEAR(level["brdf"]["e_log"].get<double>(), f.levels[1].brdf.elog_mean, 1e-5 * f.levels[1].brdf.elog_mean);
  EXPECT_NEAR(level["param"]["e_mean"].get<double>(), f.levels[1].param.emean, 1e-5 * f.levels[1].param.emean);
  // Seed 6 transmits, seed 5 does not: the transmitted figures beside the reflected ones for 6 alone.
  ASSERT_GT(draw_random_material(6).transmission, 0.0f);
  ASSERT_EQ(draw_random_material(5).transmission, 0.0f);
  ASSERT_TRUE(f.levels[1].transmits);
  EXPECT_FALSE(j["seeds"][0]["levels"][1].contains("brdf_transmission"));
  const Json& t = level["brdf_transmission"];
  EXPECT_NEAR(t["e_log_transmitted"].get<double>(), f.levels[1].transmission.elog_transmitted,
              1e-5 * f.levels[1].transmission.elog_transmitted);
  EXPECT_NEAR(t["flux_reflected"].get<double>(), f.levels[1].transmission.flux_reflected,
              1e-5 * std::abs(f.levels[1].transmission.flux_reflected));
  ASSERT_EQ(t["transmittance"].size(), 3u);
  for (std::size_t a = 0; a < 3; ++a)
    EXPECT_NEAR(t["transmittance"][a].get<double>(), f.levels[1].transmission.transmittance[a],
                1e-5 * std::abs(f.levels[1].transmission.transmittance[a]) + 1e-9);
  EXPECT_NE(ok.out.find("brdf transmitted / reflected:"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("brdf, seeds that transmit"), std::string::npos) << ok.out;

  for (const char* bad : {"--seeds 0", "--size 1", "--first-seed -1", "--seeds 2 --first-seed 18446744073709551615",
                          "--peak-weight 2", "--lean-share -0.1"}) {
    const testing::CommandResult r = bake(bad);
    EXPECT_EQ(r.status, 2) << bad;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << bad << ": " << r.err;
  }
}

}  // namespace
}  // namespace svbrdf
