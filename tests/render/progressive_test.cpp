// Progressive rendering (render/renderer.h): every pass covers the whole frame, doubling the samples
// per pixel, so a render stopped at any time is an image of the whole frame.
#include <gtest/gtest.h>

#include <atomic>
#include <climits>
#include <cstring>
#include <vector>

#include "render_test_scenes.h"

namespace svbrdf {
namespace {

TEST(Progressive, PassesDoubleTheSamplesPerPixelUpToTheCountAskedFor) {
  EXPECT_EQ(pass_starts(1), (std::vector<int>{0, 1}));
  EXPECT_EQ(pass_starts(2), (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(pass_starts(64), (std::vector<int>{0, 1, 2, 4, 8, 16, 32, 64}));
  EXPECT_EQ(pass_starts(100), (std::vector<int>{0, 1, 2, 4, 8, 16, 32, 64, 100}));
  // The largest count --spp takes: 2^30 doubled would overflow an int.
  const std::vector<int> most = pass_starts(INT_MAX);
  ASSERT_EQ(most.size(), 33u);
  EXPECT_EQ(most[31], 1 << 30);
  EXPECT_EQ(most.back(), INT_MAX);
}

Scene lit_quad() {
  Scene s;
  s.materials.push_back(test::lambertian(Rgb(0.8f)));
  test::add_quad(s, 0, glm::dmat4(1.0), 4.0f);
  s.cameras.push_back(test::perspective_camera({0, 0, 3}, {0, 0, 0}, 40.0f));
  return s;
}

// A stop asked for before the first sample (a Ctrl-C while the MIP data was built) still leaves one
// sample in every pixel: the first pass runs to its end, and nothing after it.
TEST(Progressive, AStopBeforeTheFirstSampleLeavesOneSampleInEveryPixel) {
  SceneSetup setup;
  setup.width = 50, setup.height = 40;  // not whole tiles
  setup.env = "1,1,1";
  const PreparedScene prepared(lit_quad(), setup);
  const std::atomic<bool> cancel{true};
  RenderOptions o;
  o.spp = 64;
  o.threads = 2;
  o.cancel = &cancel;
  o.integrator.footprint_scale = 1.0f;  // as below: a footprint the same at any spp
  RenderStats stats;
  const Film film = render(prepared.world(), o, &stats);
  for (std::size_t p = 0; p < film.samples.size(); ++p) ASSERT_EQ(film.samples[p], 1u) << "pixel " << p;
  EXPECT_TRUE(stats.interrupted);
  EXPECT_EQ(stats.pixel_samples_min, 1u);
  EXPECT_EQ(stats.pixel_samples_max, 1u);
  EXPECT_EQ(stats.samples, film.samples.size());

  // The first pass is the first sample of each pixel of an uninterrupted render, bit for bit.
  RenderOptions one;
  one.spp = 1;
  one.integrator.footprint_scale = 1.0f;
  const Film whole = render(prepared.world(), one);
  EXPECT_EQ(std::memcmp(film.radiance_sum.data(), whole.radiance_sum.data(), film.radiance_sum.size() * sizeof(glm::dvec3)), 0);
}

// A render that runs to its end reports spp samples in every pixel.
TEST(Progressive, AFinishedRenderHasTheCountAskedForInEveryPixel) {
  SceneSetup setup;
  setup.width = 20, setup.height = 17;
  setup.env = "1,1,1";
  const PreparedScene prepared(lit_quad(), setup);
  RenderOptions o;
  o.spp = 5;
  RenderStats stats;
  const Film film = render(prepared.world(), o, &stats);
  for (std::size_t p = 0; p < film.samples.size(); ++p) ASSERT_EQ(film.samples[p], 5u) << "pixel " << p;
  EXPECT_EQ(stats.pixel_samples_min, 5u);
  EXPECT_EQ(stats.pixel_samples_max, 5u);
  EXPECT_FALSE(stats.interrupted || stats.timed_out);
}

}  // namespace
}  // namespace svbrdf
