// The BRDF-averaged MIP maps' claims, rendered: the LOD scenes (scenes/lod.json)
// at distances ≥ 16× (every other one by default, all of them under the `long` label) and every light,
// in the default size (48×48 pixels, 256 samples per pixel for every render; `svbrdf-lod-report --full`
// renders the same at 4096). Each camera sample filters
// 1/√spp of its pixel, so at 256 spp k × d₁ reads MIP level log₂ k − 4: the tests go to 4096×, the
// first distance that reads the coarsest level (coarsest_level_distance). The noise floor is the
// relative MSE between two ground-truth renders (--filter level0) that differ only in their seed;
// filters render with a third seed (lod/comparison.h).
//
// A filter the renderer does not offer makes these tests skip with a message naming it: they test
// the MIP filters, and a level0 stand-in would prove nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <vector>

#include "lod/comparison.h"
#include "scenes/lod_scenes.h"
#include "render/renderer.h"
#include "tests/common/test_paths.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

LodManifest manifest() {
  return read_lod_manifest(fs::path(SVBRDF_BINARY_DIR) / "scenes" / "lod" / "manifest.json");
}

// The filters the renderer offers, probed without rendering any shot.
bool filters_available() {
  LodOptions o;
  o.filters = {"param", "brdf"};
  o.min_distance = 1e30;
  return run_lod_comparison(manifest(), o).filters.size() == 2;
}

#define REQUIRE_FILTERS()                                                                                          \
  if (!filters_available())                                                                                        \
  GTEST_SKIP() << "svbrdf-render does not offer --filter param and --filter brdf yet (TextureFilter lacks them, or " \
                  "the probe rendered them exactly as level0): the LOD assertions need the mip module's lookups "   \
                  "wired into the integrator"

// The nearest distance at which the filters read the coarsest MIP level: each sample's footprint is
// 1/√spp of the pixel's (render/renderer.h), so k × d₁ reads level log₂(k/√spp) of the textures, and
// every distance beyond this one reads the same 1×1 level. (At 256 spp: 4096×; at 4096 spp: 16384×.)
double coarsest_level_distance(const LodManifest& m, int spp) {
  int size = 1;
  for (const LodCase& c : m.cases) size = std::max(size, c.texture_size);
  return size / double(resolve_footprint_scale(0.0f, spp));
}

// The shots from `min_distance` on, up to the first distance that reads the coarsest level.
LodResults render(const std::vector<std::string>& cases, double min_distance, const std::vector<std::string>& lights = {},
                  int spp = 256, const std::vector<double>& distances = {}) {
  LodOptions o;
  o.distances = distances;
  o.spp = spp;
  o.min_distance = min_distance;
  o.max_distance = coarsest_level_distance(manifest(), spp);
  o.filters = {"param", "brdf"};
  o.keep_images = false;
  o.cases = cases;
  o.lights = lights;
  return run_lod_comparison(manifest(), o);
}

std::string where(const LodShot& s) {
  return s.case_name + " / " + s.view + " / " + s.light + " at " + std::to_string(int(s.multiple)) + "x";
}

// The test of a filter at a shot: relative MSE against the first ground truth at most
// `factor` × the noise floor, and flux bias at most 1 % — beyond what the ground truth's own noise
// makes of a flux bias measured against it (3 × √2·σ, σ the relative standard deviation of one
// ground truth's flux estimated from the two ground truths, lod_metrics.h flux_noise). At 256
// samples per pixel σ reaches 0.2 % on the glinty granite; at --full's 4096, a quarter of that.
void expect_matches(const LodShot& s, const std::string& filter, double factor) {
  const auto* r = s.find(filter);
  ASSERT_NE(r, nullptr) << filter << " " << where(s);
  EXPECT_LE(r->metrics.rel_mse, factor * s.floor.rel_mse) << filter << " " << where(s) << ": floor " << s.floor.rel_mse;
  EXPECT_LE(std::abs(r->metrics.flux_bias), 0.01 + 3 * std::sqrt(2.0) * s.flux_sigma)
      << filter << " " << where(s) << ": flux noise σ " << s.flux_sigma;
}

std::vector<std::string> family_names() {
  std::vector<std::string> families;
  for (const LodCase& c : manifest().cases)
    if (c.kind == "family") families.push_back(c.name);
  return families;
}

// The five families' shots from 16× on, rendered once for all the checks below.
void check_families(const LodResults& r, int distances) {

  // At every distance ≥ 16× and every light: brdf within 1.5× the noise floor and 1 % of the flux.
  // (Polished granite at its highlight — head-on under the overhead sun, and the mirror view — from
  // 256× on was 2.6–3.7 % too bright, against the 2.1–2.5 % allowed, until narrow spread cores got
  // their skirt: lobe_reduction.cpp, set_shape. The metal tray seen head-on under the 45° and 75°
  // suns is the hard case: those views see only the off-specular tail of the fingerprints' rough lobes, which a reduction to GGX lobes lost — 6 % to
  // 35 % of the flux from 64× on — until the lobes carried roughness mixtures, lobe.h.)
  int n = 0;
  for (const LodShot& s : r.shots) {
    expect_matches(s, "brdf", 1.5);
    ++n;
  }
  EXPECT_EQ(n, (5 * 4 + 2) * distances);  // five families × four lights + two mirror views, per distance

  // The control: printed paper varies only in albedo, so averaging parameters is exact for it and
  // both filters agree with the ground truth within 1.5× the noise floor.
  n = 0;
  for (const LodShot& s : r.shots) {
    if (s.case_name.rfind("printed-paper", 0) != 0) continue;
    expect_matches(s, "param", 1.5);
    ++n;
  }
  EXPECT_EQ(n, 4 * distances);

  // The mission's contrast, at 64× and beyond. Measured at this size (256 spp), at
  // 64×, 256×, 1024× and 4096×:
  //  - metal-tray: param's relative MSE is 2.4–419× brdf's (head-on sun-0: 20×, 21×, 97×, 419×; 45°
  //    and 75° suns: 12–25×, where param also loses 64–92 % of the flux; mirror view: 26×, 14×, 173×,
  //    358×; sky: 3.1×, 2.4×, 2.9×, 3.1×, with param −7 to −13 % of the flux);
  //  - painted-wall: under the 0° light param's relative MSE is 15–84× brdf's (param +0.3–0.6 % flux);
  //    under 45°, 75° and the sky param's error (+0.2–0.4 % flux) is within this size's noise floor
  //    (ratios 0.9–2.0), so those are not asserted here.
  // Asserted: param's relative MSE ≥ 3× brdf's, or param's flux bias ≥ 5 %, or its peak ratio off by
  // ≥ 2× (any one of the three metrics of lod/metrics.h shows param failing where brdf holds).
  n = 0;
  for (const LodShot& s : r.shots) {
    const bool tray = s.case_name.rfind("metal-tray", 0) == 0;
    const bool wall = s.case_name.rfind("painted-wall", 0) == 0 && s.light == "sun-0";
    if (s.multiple < 64 || !(tray || wall)) continue;
    const auto* p = s.find("param");
    const auto* b = s.find("brdf");
    ASSERT_TRUE(p && b);
    const bool mse = p->metrics.rel_mse >= 3 * b->metrics.rel_mse;
    const bool flux = std::abs(p->metrics.flux_bias) >= 0.05;
    const bool peak = p->metrics.peak_ratio >= 2 || p->metrics.peak_ratio <= 0.5;
    EXPECT_TRUE(mse || flux || peak) << where(s) << ": param " << p->metrics.rel_mse << " vs brdf " << b->metrics.rel_mse
                                     << ", param flux " << p->metrics.flux_bias << ", peak " << p->metrics.peak_ratio;
    ++n;
  }
  EXPECT_EQ(n, (5 + 1) * (distances - 1));  // metal-tray: four lights head-on + the mirror view; painted-wall:
                                             // sun-0; every distance but 16×
}

// Every family at every other distance from 16×: 16×, 256× and 4096×, levels 0, 4 and 8 of the
// default size, the first that reads the coarsest level among them (the long test below renders the
// distances between as well).
TEST(LodFilters, FamiliesAtEveryOtherDistanceFromSixteenTimesOn) {
  REQUIRE_FILTERS();
  check_families(render(family_names(), 16, {}, 256, {16, 256, 4096}), 3);
}

// All five distances from 16× to 4096× (ctest label `long`, about three minutes on 2 cores).
TEST(LodFiltersLong, FamiliesFromSixteenTimesOn) {
  if (!std::getenv("SVBRDF_LONG")) GTEST_SKIP() << "set SVBRDF_LONG=1 (ctest -L long, make test-long)";
  REQUIRE_FILTERS();
  check_families(render(family_names(), 16), 5);
}

// The same assertion at the report's --full size (4096 samples per pixel, a noise floor 16× lower) on
// the glossy families' highlights from 256× on, to 16384× where the coarsest level is read (ctest label
// `long`: `make test-long`, about 6 minutes on 2 cores). Measured, brdf's relative MSE over the floor
// at 256×, 1024×, 4096× and 16384× (allowed: 1.5×, and a flux bias of 1 % plus 0.3–0.5 % of noise):
//   metal-tray-steel head-on sun-0: 0.91, 0.60, 1.11, 1.02 (flux within 0.13 %);
//   metal-tray-steel head-on sun-45: 0.71, 0.59, 0.59, 0.53 (−0.18 to −0.61 %);
//   metal-tray-steel mirror sun-45: 0.82, 1.13, 0.77, 1.11 (within 0.14 %);
//   granite-polished head-on sun-0: 0.81, 0.97, 0.75, 0.75 (within 0.24 %);
//   granite-polished head-on sun-45: 0.93, 0.75, 0.54, 0.54 (within 0.05 %);
//   granite-polished mirror sun-45: 0.73, 1.09, 0.91, 0.83 (within 0.11 %).
// At 3000 and 6000 samples per pixel the largest is 1.11× and 1.35× (the tray's mirror view at 1024×;
// the tray head-on under the 0° sun at 16384× is 1.11×, 1.02×, 1.27× at 3000, 4096, 6000: a small bias
// of the coarsest level shows as the noise falls). The criterion is a bias against the
// truth's noise, so it tightens with the count; with pbrt-v4's footprint floor of 1/8 the tray's mirror
// view at 1024× was 1.37×, 1.59× and 3.25× at 3000, 4096 and 6000 (render/renderer.h). Before the
// coarse texels' radial correction and re-centring the granite's highlight was 1.5–3.8× and the tray's
// up to 3.4× (bench/results/mip.md). The 256-sample test above passes
// them all with a floor 16× higher.
TEST(LodFiltersLong, GlossyHighlightsAtTheReportsFullSizeFromTwoHundredFiftySixTimesOn) {
  if (!std::getenv("SVBRDF_LONG")) GTEST_SKIP() << "set SVBRDF_LONG=1 (ctest -L long, make test-long)";
  REQUIRE_FILTERS();
  const LodResults r = render({"metal-tray-steel", "granite-polished"}, 256, {"sun-0", "sun-45"}, 4096);
  int n = 0;
  for (const LodShot& s : r.shots) {
    expect_matches(s, "brdf", 1.5);
    ++n;
  }
  EXPECT_EQ(n, 2 * 3 * 4);  // two families × (two lights head-on + the mirror view) × 256× to 16384×
}

// The tile roof: the flat proxy with the baked normal distribution, under --filter brdf, matches the
// real geometry supersampled within 2× the noise floor at 64× and beyond, under the lights that
// cast no shadow on the roof (0° and 45°: its steepest slope is 34.6°) and under the sky. Under the
// 75° light the roof shadows itself, which no normal distribution represents: the proxy is 13–17 % too
// bright up to 256× (2.6× the floor at 64×; the report shows it). Under the sky the roof also hides a
// little of the sky from itself, within this size's floor.
// Measured at this size, brdf over the floor at 64×, 256×, 1024×, 4096×: 0.79,
// 0.51, 0.71, 0.69 (0°); 1.07, 0.83, 1.76, 1.84 (45°); 0.93, 0.88, 0.90, 0.88 (sky). param at 1.1×, 5.2×,
// 1900×, 1800× under the 0° sun (the averaged normal points the narrow highlight at the camera, +206 %
// flux from 1024× on). From 1024× on brdf's flux is −0.7 % (0°), −8.3 to −8.5 % (45°) and −2.3 % (sky),
// hidden at this size by the floor. It is the BRDF pyramid's own: at levels 6–8 (a whole period of the
// roof in a texel) its four lobes sit at +30°, −30°, +7° and −15° of slope for a continuum over ±34.6°,
// and the 45° sun's half vector (22.5°) falls in the gap between +7° and +30°: `svbrdf-bake eval` of
// the proxy's level 6 at wi 45° along the slopes, wo normal, is 7 %, 13 %, 17 % (R, G, B) below the
// exact mean BRDF, and within 1 % across the slopes.
TEST(LodFilters, TileRoofProxyMatchesTheGeometryFromSixtyFourTimesOn) {
  REQUIRE_FILTERS();
  const LodResults r = render({"tile-roof"}, 64, {"sun-0", "sun-45", "sky"});
  int n = 0;
  for (const LodShot& s : r.shots) {
    const auto* b = s.find("brdf");
    ASSERT_NE(b, nullptr);
    EXPECT_LE(b->metrics.rel_mse, 2.0 * s.floor.rel_mse) << where(s) << ": floor " << s.floor.rel_mse;
    ++n;
  }
  EXPECT_EQ(n, 3 * 4);  // three lights, 64× to 4096×
}

}  // namespace
}  // namespace svbrdf
