// Thin-lens depth of field (render/camera.h): the plane of focus renders as the pinhole renders it,
// and a plane off focus is blurred by the circle of confusion the thin lens predicts. The scenes are
// Lambertian planes under a uniform environment of radiance 1 rendered with BSDF sampling alone, so
// every camera sample returns its texel's albedo exactly: what remains is where the samples land.
#include <gtest/gtest.h>

#include <cmath>

#include "base/error.h"
#include "render/camera.h"
#include "render_test_scenes.h"

namespace svbrdf {
namespace {

constexpr float kYfovDeg = 30.0f;

// A plane across the view axis at distance `depth` from a perspective camera at the origin looking
// down −z, 20 m wide (wider than the frame and its blur), textured with `texture` (nearest texels).
Scene plane_scene(float depth, const Image& texture) {
  Scene s;
  MaterialDesc m = test::lambertian(Rgb(1.0f));
  m.base_color_texture.texture = test::add_image_texture(s, texture);
  s.materials.push_back(m);
  test::add_quad(s, 0, glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, -depth)), 20.0f);
  s.cameras.push_back(test::perspective_camera({0, 0, 0}, {0, 0, -1}, kYfovDeg));
  return s;
}

// A base colour texture is sRGB-encoded (glTF 2.0 §3.9.2): the linear albedo of a stored value v,
// by IEC 61966-2-1.
double albedo(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

IntegratorSettings noiseless(TextureFilter filter) {
  IntegratorSettings s;
  s.light_sampling = LightSampling::bsdf;
  s.filter = filter;
  // Eight pixels' footprints: coarse enough that the MIP level the filters read is well above 0 on the
  // planes below, so the footprints are seen.
  s.footprint_scale = 8.0f;
  return s;
}

Film render_plane(float depth, const Image& texture, int w, int h, int spp, float aperture, float focus,
                  TextureFilter filter = TextureFilter::level0, int threads = 0) {
  SceneSetup setup;
  setup.width = w, setup.height = h;
  setup.env = "1";
  setup.aperture = aperture;
  setup.focus_distance = focus;
  return test::render_scene(plane_scene(depth, texture), setup, spp, noiseless(filter), threads);
}

// 256×256 texels (0.078 m each on the 20 m plane) in a checker of 8-texel squares, albedo 0.1 and 0.9:
// squares of 0.625 m, a few across the frames below.
Image checker() {
  Image im(256, 256, 3);
  for (int j = 0; j < 256; ++j)
    for (int i = 0; i < 256; ++i)
      for (int c = 0; c < 3; ++c) im.pixels[(std::size_t(j) * 256 + i) * 3 + c] = ((i / 8 + j / 8) % 2) ? 0.9f : 0.1f;
  return im;
}

// A plane at the focus distance: every lens point sees the same point of it through a film position,
// so the image is the pinhole's (the same film positions: the lens draws its own random numbers),
// and so are the footprints (the MIP level λ), which the lens differentials keep the pixel's on the
// plane of focus. Only a sample whose rounding moves it across a texel edge may differ.
TEST(DepthOfField, ThePlaneOfFocusIsThePinholeImage) {
  const Image tex = checker();
  constexpr int kW = 48, kH = 32, kSpp = 8;
  const Film pinhole = render_plane(3.0f, tex, kW, kH, kSpp, 0.0f, 0.0f);
  const Film lens = render_plane(3.0f, tex, kW, kH, kSpp, 0.5f, 3.0f);
  const Image a = pinhole.radiance(), b = lens.radiance(), la = pinhole.mip_level(), lb = lens.mip_level();
  double sum = 0, level_error = 0, lo = 1, hi = 0, level = 0;
  for (std::size_t k = 0; k < a.pixels.size(); ++k) {
    sum += std::abs(a.pixels[k] - b.pixels[k]);
    lo = std::min<double>(lo, a.pixels[k]), hi = std::max<double>(hi, a.pixels[k]);
  }
  for (std::size_t k = 0; k < la.pixels.size(); ++k)
    level_error = std::max<double>(level_error, std::abs(la.pixels[k] - lb.pixels[k])), level += la.pixels[k] / la.pixels.size();
  EXPECT_LT(sum / double(a.pixels.size()), 1e-3) << "mean |lens - pinhole|";
  EXPECT_LT(level_error, 1e-3) << "the footprints differ";
  // The frame holds edges between 0.1 and 0.9, which a blur would move; footprints of several texels.
  EXPECT_LT(lo, albedo(0.1) + 0.01);
  EXPECT_GT(hi, albedo(0.9) - 0.01);
  EXPECT_GT(level, 1.5);
}

// Off focus, a point at depth d spreads over a disk of radius r = A·|d − F|/(F·d) in the image plane
// at distance 1 (camera.h), r / (2·tan(yfov/2)/H) pixels. A vertical edge's line spread function (the
// difference of the rows' mean profile across it) is the pinhole's convolved with the disk's
// projection onto x, (2/(πr²))·√(r² − x²), whose variance is r²/4: variances add, so the measured
// radius is 2·√(σ² − σ²_pinhole). It follows the prediction for two apertures, and doubles with the
// aperture.
TEST(DepthOfField, BlurGrowsWithTheApertureAsTheCircleOfConfusion) {
  Image edge(2, 1, 3);
  edge.pixels = {0.1f, 0.1f, 0.1f, 0.9f, 0.9f, 0.9f};  // left half dark, right half light
  constexpr int kW = 64, kH = 8, kSpp = 256;  // 7.5 pixels of blur per metre of lens radius below
  constexpr float kDepth = 2.0f, kFocus = 1.0f;
  const double pixel = 2.0 * std::tan(glm::radians(double(kYfovDeg)) / 2.0) / kH;
  auto lsf_variance = [&](float aperture) {
    const Image im = render_plane(kDepth, edge, kW, kH, kSpp, aperture, kFocus).radiance();
    std::vector<double> profile(kW, 0.0);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) profile[std::size_t(x)] += im.at(x, y, 1) / kH;
    // The line spread function between pixel centres x and x + 1, at x + 1/2.
    double mass = 0, mean = 0, second = 0;
    for (int x = 0; x + 1 < kW; ++x) {
      const double w = profile[std::size_t(x) + 1] - profile[std::size_t(x)], at = x + 0.5;
      mass += w, mean += w * at, second += w * at * at;
    }
    EXPECT_NEAR(mass, albedo(0.9) - albedo(0.1), 0.01) << "the whole step lies inside the frame";
    mean /= mass;
    return second / mass - mean * mean;
  };
  const double base = lsf_variance(0.0f);
  double measured[2];
  const float apertures[2] = {0.4f, 0.8f};  // radii of 3 and 6 pixels
  for (int k = 0; k < 2; ++k) {
    const double predicted = apertures[k] * std::abs(kDepth - kFocus) / (kFocus * kDepth) / pixel;
    measured[k] = 2.0 * std::sqrt(std::max(0.0, lsf_variance(apertures[k]) - base));
    // 256 samples a pixel over 8 rows: the second moment's noise is a few per cent of r².
    EXPECT_NEAR(measured[k], predicted, 0.08 * predicted) << "aperture " << apertures[k];
  }
  EXPECT_NEAR(measured[1] / measured[0], 2.0, 0.15);
}

// The lens keeps the render bit-identical for any thread count: its point comes from the sample's
// own random numbers.
TEST(DepthOfField, BitIdenticalForAnyThreadCount) {
  const Image tex = checker();
  const Film one = render_plane(2.5f, tex, 24, 16, 4, 0.3f, 0.0f, TextureFilter::param, 1);
  const Film two = render_plane(2.5f, tex, 24, 16, 4, 0.3f, 0.0f, TextureFilter::param, 2);
  EXPECT_EQ(one.radiance().pixels, two.radiance().pixels);
}

// The default focus distance is the autofocus's: along the view axis to the surface at the frame's
// centre.
TEST(DepthOfField, AutofocusIsTheDistanceToTheCentresSurface) {
  SceneSetup setup;
  setup.width = 16, setup.height = 8;
  setup.aperture = 0.1f;
  const PreparedScene prepared(plane_scene(2.75f, checker()), setup);
  EXPECT_TRUE(prepared.camera().has_lens());
  EXPECT_NEAR(prepared.camera().focus_distance(), 2.75f, 1e-4f);
  setup.focus_distance = -1.0f;
  EXPECT_THROW({ const PreparedScene bad(plane_scene(2.75f, checker()), setup); }, Error);
}

}  // namespace
}  // namespace svbrdf
