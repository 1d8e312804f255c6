// A render's alpha: the share of a pixel's camera samples that are opaque (render/integrator.h,
// PathSample::opaque), which for a transparent background is the share of the pixel the scene covers.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include "gltf_test_files.h"
#include "render_program.h"
#include "render_test_scenes.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

constexpr int kSide = 32;  // pixels; the orthographic frame spans [−1, 1]², a pixel 1/16 wide
constexpr int kSpp = 256;

// A unit square, lit by the environment, shifted by a quarter of a pixel right and up so that its
// edges cut pixels: its left edge covers 3/4 of column 8, its right edge 1/4 of column 24, its top
// edge 1/4 of row 7, its bottom edge 3/4 of row 23 (rows from the top).
Scene square_in_frame() {
  Scene s;
  s.materials.push_back(test::lambertian(Rgb(0.5f)));
  test::add_quad(s, 0, glm::translate(glm::dmat4(1.0), glm::dvec3(1.0 / 64, 1.0 / 64, 0)), 1.0f);
  s.cameras.push_back(test::ortho_camera({0, 0, 3}, {0, 0, 0}, 1.0f));
  return s;
}

// The share of pixel (x, y) the square covers, from its edges in pixel units.
double coverage(int x, int y) {
  const auto overlap = [](int pixel, double lo, double hi) { return std::clamp(std::min(hi, pixel + 1.0) - std::max(lo, double(pixel)), 0.0, 1.0); };
  return overlap(x, 8.25, 24.25) * overlap(y, 7.75, 23.75);
}

Film render_square(bool background) {
  SceneSetup setup;
  setup.width = setup.height = kSide;
  setup.env = "1,1,1";
  const PreparedScene prepared(square_in_frame(), setup);
  RenderOptions o;
  o.spp = kSpp;
  o.seed = 3;
  o.integrator.background = background;
  return render(prepared.world(), o);
}

// Against a transparent background alpha is the coverage: 1 inside, 0 outside, and on the edges the
// covered share within the noise of kSpp uniformly jittered samples (4.5σ of a Bernoulli mean). The
// colour is premultiplied: black outside, and inside the same as with the background drawn, bit for
// bit (the environment lights the square all the same).
TEST(Alpha, AgainstATransparentBackgroundAlphaIsTheCoverage) {
  const Film clear = render_square(false), drawn = render_square(true);
  const Image alpha = clear.alpha(), rgb = clear.radiance(), drawn_rgb = drawn.radiance(), drawn_alpha = drawn.alpha();
  int edges = 0;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x) {
      const double c = coverage(x, y);
      const float a = alpha.at(x, y, 0);
      if (c == 1.0) {
        EXPECT_EQ(a, 1.0f) << x << "," << y;
        for (int k = 0; k < 3; ++k) EXPECT_EQ(rgb.at(x, y, k), drawn_rgb.at(x, y, k)) << x << "," << y;
      } else if (c == 0.0) {
        EXPECT_EQ(a, 0.0f) << x << "," << y;
        for (int k = 0; k < 3; ++k) EXPECT_EQ(rgb.at(x, y, k), 0.0f) << x << "," << y;
      } else {
        ++edges;
        EXPECT_NEAR(a, c, 4.5 * std::sqrt(c * (1.0 - c) / kSpp)) << x << "," << y;
      }
      // With the environment drawn every sample is opaque.
      EXPECT_EQ(drawn_alpha.at(x, y, 0), 1.0f) << x << "," << y;
    }
  EXPECT_EQ(edges, 2 * 16 + 2 * 16);  // four edges of 16 pixels each, the corners among them
}

// svbrdf-render --transparent: the EXR is RGBA (OpenImageIO's tools see its alpha channel) with
// alpha 0 where the quad is not, and the PNG has straight alpha.
TEST(Alpha, TheProgramWritesRgbaAndATransparentPng) {
  test::TempDir dir;
  const std::string q = dir.write("q.gltf", test::GltfQuad().json()).string();
  const fs::path exr = dir.path() / "t.exr";
  const test::RenderRun r = test::render({q, "-q", "--transparent", "--res", "24x16", "--spp", "4", "-o", exr.string()}, dir.path());
  ASSERT_TRUE(r.end.exited && r.end.code == 0) << r.err;
  const std::string info = test::oiiotool_info(exr, dir.path());
  if (info.find("not found") != std::string::npos) GTEST_SKIP() << "oiiotool is not installed";
  EXPECT_NE(info.find("channel list: R, G, B, A"), std::string::npos) << info;
  const Image im = read_image(exr), png = read_image(fs::path(exr).replace_extension(".png"));
  ASSERT_EQ(im.channels, 4);
  ASSERT_EQ(png.channels, 4);
  // The framing camera (render_setup.h) leaves a margin around the quad: its corner pixel is empty.
  EXPECT_EQ(im.at(0, 0, 3), 0.0f);
  EXPECT_EQ(png.at(0, 0, 3), 0.0f);
  EXPECT_EQ(im.at(12, 8, 3), 1.0f);
  EXPECT_EQ(png.at(12, 8, 3), 1.0f);
}

}  // namespace
}  // namespace svbrdf
