// The MIP lookups honour the glTF wrap modes per axis at every level (mip_lookup.h): at level 0 the
// filter is the sampler's bilinear lookup (textures/sampler.h, a separate code path); at a coarse
// level a clamped axis repeats the level's edge texel and never reaches the opposite edge, and a
// mirrored axis reads the mirror image. Values come from closed forms over a ramp whose texel value
// is its column (or row) index, so a coarse texel's value is the mean of the indices it covers.
#include <gtest/gtest.h>

#include <map>
#include <tuple>

#include "mip/mip_lookup.h"
#include "textures/sampler.h"

namespace svbrdf {
namespace {

constexpr WrapMode kModes[] = {WrapMode::repeat, WrapMode::clamp_to_edge, WrapMode::mirrored_repeat};

// w×h texels whose base colour red is column + 10·row (green: row), as an Image for the sampler and
// as a parameter pyramid for the MIP lookups.
Image ramp_image(int w, int h) {
  Image im(w, h, 3);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      float* p = &im.pixels[(static_cast<std::size_t>(j) * w + i) * 3];
      p[0] = static_cast<float>(i + 10 * j), p[1] = static_cast<float>(j), p[2] = 0.0f;
    }
  return im;
}
ParamPyramid ramp_pyramid(int w, int h) {
  MaterialTexels m(w, h);
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) m.base_color[m.index(i, j)] = glm::vec3(i + 10 * j, j, 0);
  return ParamPyramid::build(m);
}

// An isotropic footprint `texels` level-0 texels of a w-wide texture across, centred at uv.
Footprint square(glm::vec2 uv, float texels, int w) { return {uv, {texels / w, 0}, {0, texels / w}}; }

// At a footprint below one texel the parameter filter reads level 0 bilinearly: the sampler's lookup
// under each mode, wherever uv lies (a 5×3 ramp: odd and even sides, far outside the texture).
TEST(WrapLookup, LevelZeroIsTheSamplersBilinearLookup) {
  const Image img = ramp_image(5, 3);
  const ParamPyramid p = ramp_pyramid(5, 3);
  for (WrapMode ms : kModes)
    for (WrapMode mt : kModes) {
      const Sampler s{FilterMode::bilinear, ms, mt};
      for (float u = -3.0f; u <= 3.0f; u += 0.037f)
        for (float v : {-1.3f, -0.02f, 0.1f, 0.5f, 0.97f, 1.01f, 2.6f}) {
          const glm::vec3 got = filter_params(p, {{u, v}, {1e-4f, 0}, {0, 1e-4f}}, s.wrap()).base_color;
          const glm::vec4 want = sample(img, s, {u, v});
          EXPECT_NEAR(got.r, want.r, 2e-5f) << int(ms) << int(mt) << " at " << u << "," << v;
          EXPECT_NEAR(got.g, want.g, 2e-5f) << int(ms) << int(mt) << " at " << u << "," << v;
        }
    }
}

// Level 2 of a 16-wide ramp: texel k covers columns 4k..4k+3, mean 4k + 1.5. A footprint 4 texels
// across reads level 2 alone, bilinearly at x = 4u − 0.5 in its texels.
TEST(WrapLookup, CoarseLevelAtTheEdgesMatchesTheClosedForm) {
  const ParamPyramid p = ramp_pyramid(16, 16);
  const float row = 0.5f;  // v at the middle: level-2 rows 1 and 2, half each → the mean of rows 4..11
  auto red = [&](float u, WrapMode m) {
    return filter_params(p, square({u, row}, 4.0f, 16), {m, WrapMode::repeat}).base_color.r - 10.0f * 7.5f;
  };
  auto level2 = [](int k) { return 4.0f * k + 1.5f; };
  // At u = 0 the taps are texels −1 and 0, half each: repeat wraps −1 to 3; clamp and mirror read 0.
  EXPECT_NEAR(red(0.0f, WrapMode::repeat), 0.5f * (level2(3) + level2(0)), 1e-4f);
  EXPECT_NEAR(red(0.0f, WrapMode::clamp_to_edge), level2(0), 1e-4f);
  EXPECT_NEAR(red(0.0f, WrapMode::mirrored_repeat), level2(0), 1e-4f);
  // Past the edge: clamp stays on the edge texel however far; mirror reads u's mirror image.
  for (float u : {-0.3f, -2.0f, -1e6f}) EXPECT_NEAR(red(u, WrapMode::clamp_to_edge), level2(0), 1e-4f) << u;
  for (float u : {1.05f, 1.5f, 7.0f}) EXPECT_NEAR(red(u, WrapMode::clamp_to_edge), level2(3), 1e-4f) << u;
  EXPECT_NEAR(red(-0.25f, WrapMode::mirrored_repeat), 0.5f * (level2(0) + level2(1)), 1e-4f);  // x = 0.5 mirrored
  // Mirrored repeat is even about 0 and about 1, and has period 2, at every level.
  for (float texels : {1.0f, 2.0f, 4.0f, 8.0f, 16.0f})
    for (float u = 0.0f; u <= 1.0f; u += 0.0371f) {
      auto at = [&](float x) { return filter_params(p, square({x, row}, texels, 16), {WrapMode::mirrored_repeat, WrapMode::repeat}).base_color.r; };
      EXPECT_NEAR(at(-u), at(u), 1e-3f) << texels << " " << u;
      EXPECT_NEAR(at(2.0f - u), at(u), 1e-3f) << texels << " " << u;
      EXPECT_NEAR(at(u + 2.0f), at(u), 1e-3f) << texels << " " << u;
    }
}

// A footprint that crosses a clamped edge (anisotropic, its probes reaching past it, trilinear) takes
// no tap from the opposite half of the texture, under both the deterministic taps and the stochastic
// selection; the selection's frequencies are the taps' weights under the same wrap modes.
TEST(WrapLookup, FootprintsAcrossAClampedEdgeStayOnThatEdge) {
  const Extent e{64, 32};
  const int levels = level_count(e);
  const WrapModes clamp{WrapMode::clamp_to_edge, WrapMode::clamp_to_edge};
  // Across the top-left corner: 12 texels along u, 3 along v, between levels.
  const Footprint f{{0.01f, -0.02f}, {12.0f / 64, 0.5f / 32}, {0.4f / 64, 3.0f / 32}};
  const FilterTaps taps = filter_taps(e, levels, f, clamp);
  ASSERT_GT(taps.count, 4);
  EXPECT_GT(taps.probes, 1);
  std::map<std::tuple<int, int, int>, double> want;
  for (int k = 0; k < taps.count; ++k) {
    const FilterTap& t = taps.taps[static_cast<std::size_t>(k)];
    const Extent le = level_extent(e, t.level);
    EXPECT_LT(t.i, (le.width + 1) / 2) << "level " << t.level;
    EXPECT_LT(t.j, (le.height + 1) / 2) << "level " << t.level;
    want[{t.level, t.i, t.j}] += t.weight;
  }
  constexpr int kDraws = 1 << 16;
  std::map<std::tuple<int, int, int>, double> got;
  for (int k = 0; k < kDraws; ++k) {
    const FilterTap t = select_tap(e, levels, f, (static_cast<float>(k) + 0.5f) / kDraws, clamp);
    got[{t.level, t.i, t.j}] += 1.0 / kDraws;
  }
  // u on a grid of 2^16 points: each stage's split is exact to a few grid steps.
  for (const auto& [tap, w] : got) EXPECT_NEAR(w, want[tap], 1e-3) << std::get<0>(tap) << " " << std::get<1>(tap) << " " << std::get<2>(tap);
  for (const auto& [tap, w] : want) EXPECT_NEAR(got[tap], w, 1e-3);
}

}  // namespace
}  // namespace svbrdf
