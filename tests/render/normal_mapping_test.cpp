// Normal maps in the renderer. As microsurfaces (NormalMapping::microfacet,
// appearance/microfacet_normal_mapping.h): a strong normal map keeps a white furnace's energy and
// leaves no black crescent under a grazing sun. As the mapped normal (NormalMapping::shading, the
// default): no texel the viewer sees is black for facing away from the viewer.
#include <gtest/gtest.h>

#include <cmath>

#include "render_test_scenes.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

using test::add_quad;
using test::lambertian;
using test::ortho_camera;
using test::render_scene;

constexpr int kTexels = 64;

// The tangent-space normal of the height field h = A·sin(2πkx/N)·sin(2πky/N) (texel units), with A
// chosen so the steepest slope is 70° off the normal: a strong map, as sculpted details give.
glm::vec3 bump_normal(int x, int y) {
  const double k = 2.0, w = 2.0 * 3.141592653589793 * k / kTexels;
  const double amplitude = std::tan(70.0 * 3.141592653589793 / 180.0) / w;
  const double fx = (x + 0.5) * w, fy = (y + 0.5) * w;
  const double dhdx = amplitude * w * std::cos(fx) * std::sin(fy), dhdy = amplitude * w * std::sin(fx) * std::cos(fy);
  return glm::normalize(glm::vec3(float(-dhdx), float(-dhdy), 1.0f));
}

// A white Lambertian square (side `size`, facing +z) carrying the bump map, seen straight down. The
// map repeats size/2 times along each side, so the bumps keep their size whatever the square's.
Scene bumpy_plane(float size = 2.0f) {
  Scene s;
  Image map(kTexels, kTexels, 3);
  for (int y = 0; y < kTexels; ++y)
    for (int x = 0; x < kTexels; ++x)
      for (int c = 0; c < 3; ++c)
        map.pixels[(std::size_t(y) * kTexels + x) * 3 + std::size_t(c)] = 0.5f * bump_normal(x, y)[c] + 0.5f;
  MaterialDesc m = lambertian(Rgb(1.0f));
  m.normal_texture.texture = test::add_image_texture(s, std::move(map));
  s.materials.push_back(m);
  add_quad(s, 0, glm::dmat4(1.0), size);
  for (auto& uv : s.meshes.back().primitives[0].texcoords[0]) uv *= 0.5f * size;
  s.cameras.push_back(ortho_camera({0, 0, 5}, {0, 0, 0}, 1.0f));
  return s;
}

IntegratorSettings level0(NormalMapping mode = NormalMapping::microfacet) {
  IntegratorSettings integ;
  integ.filter = TextureFilter::level0;  // the normal map read texel by texel, shaded by SurfaceBsdf
  integ.normal_mapping = mode;
  return integ;
}

// The white furnace: a white, non-absorbing microsurface in a uniform environment of radiance L
// reflects L in every direction (what the facets scatter stays in the microsurface until it
// leaves), however steep its normal map.
TEST(NormalMapping, StrongMapKeepsTheFurnacesEnergy) {
  SceneSetup setup;
  setup.width = setup.height = 32;
  setup.env = "0.5,0.5,0.5";
  const Image im = render_scene(bumpy_plane(), setup, 256, level0()).radiance();
  double sum = 0.0;
  float lo = 1e9f, hi = 0.0f;
  for (int p = 0; p < 32 * 32; ++p) {
    const float v = im.pixels[std::size_t(p) * im.channels];
    sum += v;
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  const double mean = sum / (32 * 32);
  std::printf("furnace: mean %.5f (environment 0.5), pixels in [%.4f, %.4f]\n", mean, lo, hi);
  EXPECT_NEAR(mean, 0.5, 0.005);  // 1 % of the environment
  EXPECT_GT(lo, 0.5f * 0.85f);
  EXPECT_LT(hi, 0.5f * 1.15f);
}

// A sun 15° above the horizon: where the mapped normal turns away from it (a quarter of the texels
// here) the geometric surface is still lit, and so is every pixel, from every view: straight down,
// and 40° and 70° from the normal on the sun's side, across it and facing it. The oblique views
// see texels whose mapped normal turns from the viewer, shaded only through the tangent facet.
TEST(NormalMapping, NoBlackCrescentUnderAGrazingSun) {
  const float elevation = glm::radians(15.0f);
  const glm::vec3 to_sun(std::cos(elevation), 0.0f, std::sin(elevation));
  int away = 0;
  for (int y = 0; y < kTexels; ++y)
    for (int x = 0; x < kTexels; ++x) away += glm::dot(bump_normal(x, y), to_sun) <= 0.0f;
  ASSERT_GT(away, kTexels * kTexels / 10) << "the map must turn some normals from the sun for the test to mean anything";

  struct View {
    double theta, phi;  // of the camera, degrees from the normal and from the sun's azimuth
  };
  const View views[] = {{0, 0}, {40, 0}, {40, 90}, {40, 180}, {70, 0}, {70, 90}, {70, 180}};
  for (const View& v : views) {
    // Side 8: an orthographic view of half height 1 at 70° covers 2/cos 70° ≈ 5.8 of it, all plane.
    Scene s = bumpy_plane(8.0f);
    const double t = glm::radians(v.theta), p = glm::radians(v.phi);
    const glm::vec3 eye =
        5.0f * glm::vec3(float(std::sin(t) * std::cos(p)), float(std::sin(t) * std::sin(p)), float(std::cos(t)));
    s.cameras[0] = v.theta == 0 ? ortho_camera(eye, {0, 0, 0}, 1.0f) : ortho_camera(eye, {0, 0, 0}, 1.0f, {0, 0, 1});
    LightDesc sun;
    sun.type = LightDesc::Type::directional;
    sun.intensity = 3.0f;
    sun.direction = -to_sun;
    s.lights.push_back(sun);
    SceneSetup setup;
    setup.width = setup.height = 64;  // about a pixel a texel
    setup.env = "0,0,0";
    const Image im = render_scene(std::move(s), setup, 16, level0()).radiance();
    int black = 0;
    for (int px = 0; px < 64 * 64; ++px) black += !(im.pixels[std::size_t(px) * im.channels] > 0.0f);
    EXPECT_EQ(black, 0) << "camera " << v.theta << "° from the normal, " << v.phi << "° from the sun's azimuth";
  }
}

// The default shading by the mapped normal: seen 70° from the normal with the sun behind the
// viewer, the texels whose mapped normal faces away from the viewer (a fifth of them here) would
// shade black; turned toward the viewer (keep_reflection_above) they face the sun too, and no pixel
// is black.
TEST(NormalMapping, ShadingNormalsFacingAwayFromTheViewerAreTurnedBack) {
  const double t = glm::radians(70.0);
  const glm::vec3 to_eye(float(std::sin(t)), 0.0f, float(std::cos(t)));
  int away = 0;
  for (int y = 0; y < kTexels; ++y)
    for (int x = 0; x < kTexels; ++x) away += glm::dot(bump_normal(x, y), to_eye) <= 0.0f;
  ASSERT_GT(away, kTexels * kTexels / 10) << "the map must turn some normals from the viewer for the test to mean anything";
  for (const NormalMapping mode : {NormalMapping::shading, NormalMapping::microfacet}) {
    Scene s = bumpy_plane(8.0f);
    s.cameras[0] = ortho_camera(5.0f * to_eye, {0, 0, 0}, 1.0f, {0, 0, 1});
    LightDesc sun;
    sun.type = LightDesc::Type::directional;
    sun.intensity = 3.0f;
    const float elevation = glm::radians(25.0f);
    sun.direction = -glm::vec3(std::cos(elevation), 0.0f, std::sin(elevation));
    s.lights.push_back(sun);
    SceneSetup setup;
    setup.width = setup.height = 64;
    setup.env = "0,0,0";
    const Image im = render_scene(std::move(s), setup, 16, level0(mode)).radiance();
    int black = 0;
    for (int px = 0; px < 64 * 64; ++px) black += !(im.pixels[std::size_t(px) * im.channels] > 0.0f);
    EXPECT_EQ(black, 0) << (mode == NormalMapping::shading ? "shading" : "microfacet");
  }
}

}  // namespace
}  // namespace svbrdf
