// Issue 7's assertions on the BRDF-averaged MIP maps, rendered: the LOD scenes (scenes/lod.json)
// at every distance ≥ 16× and every light, in the default size (48×48 pixels, 256 samples per pixel
// for every render; `svbrdf-lod-report --full` renders the same at 4096). The noise floor is the
// relative MSE between two ground-truth renders (--filter level0) that differ only in their seed;
// filters render with a third seed (scenes/lod_comparison.h).
//
// A filter the renderer does not offer makes these tests skip with a message naming it: they test
// the MIP filters, and a level0 stand-in would prove nothing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "scenes/lod_comparison.h"
#include "scenes/lod_scenes.h"

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

LodResults render(const std::vector<std::string>& cases, double min_distance, const std::vector<std::string>& lights = {}) {
  LodOptions o;
  o.spp = 256;
  o.min_distance = min_distance;
  o.filters = {"param", "brdf"};
  o.keep_images = false;
  o.cases = cases;
  o.lights = lights;
  return run_lod_comparison(manifest(), o);
}

std::string where(const LodShot& s) {
  return s.case_name + " / " + s.view + " / " + s.light + " at " + std::to_string(int(s.multiple)) + "x";
}

// One render of the five families at 16× and beyond (one ctest entry, so the renders are shared).
TEST(LodFilters, FamiliesFromSixteenTimesOn) {
  REQUIRE_FILTERS();
  std::vector<std::string> families;
  for (const LodCase& c : manifest().cases)
    if (c.kind == "family") families.push_back(c.name);
  const LodResults r = render(families, 16);

  // At every distance ≥ 16× and every light: brdf's relative MSE against the first ground truth is
  // at most 1.5× the noise floor, and its flux bias at most 1 %.
  int n = 0;
  for (const LodShot& s : r.shots) {
    const auto* b = s.find("brdf");
    ASSERT_NE(b, nullptr);
    EXPECT_LE(b->metrics.rel_mse, 1.5 * s.floor.rel_mse) << where(s) << ": floor " << s.floor.rel_mse;
    EXPECT_LE(std::abs(b->metrics.flux_bias), 0.01) << where(s) << ": the floor's flux difference " << s.floor.flux_bias;
    ++n;
  }
  EXPECT_EQ(n, (5 * 4 + 2) * 4);  // five families × four lights + two mirror views, four distances

  // The control: printed paper varies only in albedo, so averaging parameters is exact for it and
  // both filters agree with the ground truth within 1.5× the noise floor.
  n = 0;
  for (const LodShot& s : r.shots) {
    if (s.case_name.rfind("printed-paper", 0) != 0) continue;
    const auto* p = s.find("param");
    ASSERT_NE(p, nullptr);
    EXPECT_LE(p->metrics.rel_mse, 1.5 * s.floor.rel_mse) << "param " << where(s) << ": floor " << s.floor.rel_mse;
    ++n;
  }
  EXPECT_EQ(n, 4 * 4);
}

// The tile roof: the flat proxy with the baked normal distribution, under --filter brdf, matches the
// real geometry supersampled within 2× the noise floor at 64× and beyond, under the lights that
// cast no shadow on the roof (0° and 45°: its steepest slope is 34.6°). Under the 75° light the
// roof shadows itself and under the sky it occludes part of it; no normal distribution represents
// that (the report shows those cases).
TEST(LodFilters, TileRoofProxyMatchesTheGeometryFromSixtyFourTimesOn) {
  REQUIRE_FILTERS();
  const LodResults r = render({"tile-roof"}, 64, {"sun-0", "sun-45"});
  int n = 0;
  for (const LodShot& s : r.shots) {
    const auto* b = s.find("brdf");
    ASSERT_NE(b, nullptr);
    EXPECT_LE(b->metrics.rel_mse, 2.0 * s.floor.rel_mse) << where(s) << ": floor " << s.floor.rel_mse;
    ++n;
  }
  EXPECT_EQ(n, 2 * 3);
}

}  // namespace
}  // namespace svbrdf
