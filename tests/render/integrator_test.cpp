// Closed-form checks of the path tracer: every expectation comes from a formula
// or a property, never from the renderer's own output.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gltf_test_files.h"
#include "appearance/gltf.h"
#include "appearance/eon.h"
#include "appearance/gltf_surface_bsdf.h"
#include "render_test_scenes.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

using test::add_quad;
using test::add_sphere;
using test::lambertian;
using test::ortho_camera;
using test::render_scene;

constexpr float kPiF = 3.14159265358979f;

glm::vec3 pixel(const Image& im, int x, int y) {
  const float* p = &im.pixels[(std::size_t(y) * im.width + x) * im.channels];
  return {p[0], p[1], p[2]};
}

// Units: a Lambertian quad of albedo ρ facing a directional light of intensity E at
// incidence θ, seen by any camera with a black environment, has pixel value ρ/π·E·cosθ exactly.
TEST(Integrator, LambertianQuadUnderDirectionalLight) {
  const Rgb rho(0.2f, 0.5f, 0.8f);
  const float E = 3.0f, theta = glm::radians(60.0f);
  for (int view = 0; view < 2; ++view) {
    Scene s;
    s.materials.push_back(lambertian(rho));
    add_quad(s, 0, glm::dmat4(1.0), 8.0f);
    LightDesc sun;
    sun.type = LightDesc::Type::directional;
    sun.intensity = E;
    sun.direction = -glm::vec3(std::sin(theta), 0.0f, std::cos(theta));
    s.lights.push_back(sun);
    // Head-on, and from 50° off the normal on the other side.
    s.cameras.push_back(view == 0 ? ortho_camera({0, 0, 5}, {0, 0, 0}, 1.0f)
                                  : ortho_camera({-5 * std::sin(0.87f), 0, 5 * std::cos(0.87f)}, {0, 0, 0}, 1.0f));
    SceneSetup setup;
    setup.width = setup.height = 16;
    setup.env = "0,0,0";
    const Image im = render_scene(std::move(s), setup, 4).radiance();
    const Rgb expected = rho / kPiF * E * std::cos(theta);
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) {
        const glm::vec3 v = pixel(im, x, y);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(v[c], expected[c], 2e-6f * expected[c]) << "view " << view;
      }
  }
}

// A point light of radiant intensity I at height d above the quad: E = I·cosθ/r² = I·d/r³.
TEST(Integrator, PointLightInverseSquare) {
  const float I = 5.0f, d = 1.5f;
  Scene s;
  s.materials.push_back(lambertian(Rgb(0.6f)));
  add_quad(s, 0, glm::dmat4(1.0), 8.0f);
  LightDesc l;
  l.type = LightDesc::Type::point;
  l.intensity = I;
  l.position = {0.0f, 0.0f, d};
  s.lights.push_back(l);
  s.cameras.push_back(ortho_camera({0, 0, 5}, {0, 0, 0}, 1.0f));
  SceneSetup setup;
  setup.width = setup.height = 256;
  setup.env = "0,0,0";
  const Image im = render_scene(std::move(s), setup, 8).radiance();
  for (int y = 0; y < 256; y += 37)
    for (int x = 0; x < 256; x += 37) {
      const glm::vec2 q((x + 0.5f) / 128.0f - 1.0f, 1.0f - (y + 0.5f) / 128.0f);
      const float r = std::sqrt(glm::dot(q, q) + d * d);
      const float expected = 0.6f / kPiF * I * d / (r * r * r);
      // A pixel is the mean over its area at jittered positions: with |∇E|/E ≤ 1.3 and pixels 1/128
      // wide, 8 samples scatter by ≤ 0.1 %; 0.5 % is five of those.
      EXPECT_NEAR(pixel(im, x, y).x, expected, 5e-3f * expected) << x << "," << y;
    }
}

// Spot cone and range window of KHR_lights_punctual.
TEST(Integrator, SpotConeAndRange) {
  const float d = 1.0f;
  Scene s;
  s.materials.push_back(lambertian(Rgb(1.0f)));
  add_quad(s, 0, glm::dmat4(1.0), 8.0f);
  LightDesc l;
  l.type = LightDesc::Type::spot;
  l.intensity = 2.0f;
  l.position = {0.0f, 0.0f, d};
  l.direction = {0.0f, 0.0f, -1.0f};
  l.inner_cone = 0.2f;
  l.outer_cone = 0.4f;
  l.range = 1.2f;
  s.lights.push_back(l);
  s.cameras.push_back(ortho_camera({0, 0, 5}, {0, 0, 0}, 1.0f));
  SceneSetup setup;
  setup.width = setup.height = 64;
  setup.env = "0,0,0";
  const Image im = render_scene(std::move(s), setup, 4).radiance();
  // Centre: inside the inner cone, r = d: E = I/d²·(1 − (d/range)^4).
  const float window = 1.0f - std::pow(d / 1.2f, 4.0f);
  const float centre = (pixel(im, 31, 31).x + pixel(im, 32, 32).x + pixel(im, 31, 32).x + pixel(im, 32, 31).x) / 4;
  EXPECT_NEAR(centre, 1.0f / kPiF * 2.0f * window, 2e-3f);
  // A corner is at 54° from the axis, outside the outer cone: black.
  EXPECT_EQ(pixel(im, 0, 0).x, 0.0f);
}

// The white furnace: an albedo-1 Lambertian sphere inside a uniform environment of radiance L
// reflects exactly L everywhere (convex, flat-shaded: every bounce leaves for the environment).
TEST(Integrator, WhiteFurnace) {
  Scene s;
  s.materials.push_back(lambertian(Rgb(1.0f)));
  add_sphere(s, 0, 1.0f);
  s.cameras.push_back(test::perspective_camera({0, 0, 3.5f}, {0, 0, 0}, 40.0f));
  SceneSetup setup;
  setup.width = setup.height = 24;
  setup.env = "0.7,0.7,0.7";
  const Image im = render_scene(std::move(s), setup, 64).radiance();
  double sum = 0.0;
  float lo = 1e9f, hi = -1e9f;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 24; ++x) {
      const float v = pixel(im, x, y).y;
      sum += v;
      lo = std::min(lo, v), hi = std::max(hi, v);
    }
  EXPECT_NEAR(sum / (24 * 24), 0.7, 0.7 * 0.005);
  EXPECT_GT(lo, 0.7f * 0.85f);
  EXPECT_LT(hi, 0.7f * 1.15f);
}

// An environment that is 1 above the horizon and 0 below, as an equirectangular image.
std::string sky_ground_env(const test::TempDir& dir) {
  Image env(4, 2, 3);
  for (int i = 0; i < 4; ++i)
    for (int c = 0; c < 3; ++c) env.at(i, 0, c) = 1.0f;
  const auto path = dir.path() / "sky.exr";
  write_image(path, env, PixelFormat::float32);
  return path.string();
}

// A horizontal surface (front face +y) seen by an orthographic camera θ off the normal, from above
// (looking down) or below.
Image view_horizontal_surface(const MaterialDesc& m, float theta, bool from_below, const std::string& env,
                              int spp = 16) {
  Scene s;
  s.materials.push_back(m);
  add_quad(s, 0, glm::rotate(glm::dmat4(1.0), glm::radians(-90.0), glm::dvec3(1, 0, 0)), 20.0f);
  const glm::vec3 eye = 5.0f * glm::vec3(0.0f, (from_below ? -1.0f : 1.0f) * std::cos(theta), std::sin(theta));
  s.cameras.push_back(ortho_camera(eye, {0, 0, 0}, 0.5f, {0, 0, -1}));
  SceneSetup setup;
  setup.width = setup.height = 8;
  setup.env = env;
  return render_scene(std::move(s), setup, spp).radiance();
}

// Every pixel of an orthographic view of a plane sees the same angle: their mean.
float image_mean(const Image& im, int c) {
  double sum = 0.0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) sum += pixel(im, x, y)[c];
  return float(sum / (im.width * im.height));
}

// A smooth metal mirror reflects the sky with glTF's Fresnel: F = c + (1 − c)(1 − cosθ)^5.
TEST(Integrator, MirrorAgainstFresnel) {
  test::TempDir dir;
  const std::string env = sky_ground_env(dir);
  MaterialDesc m;
  m.base_color = Rgb(0.5f, 0.25f, 0.9f);
  m.metallic = 1.0f;
  m.roughness = 0.0f;
  // Roughness 0 is glTF's GGX at α = 1e-3, not an impulse: a VNDF sample now and then lands in the
  // lobe's long tail, where MIS gives most of its weight to the environment's sampling, so a single
  // sample can be 0.2 where the mean is 0.9 (and an environment sample, rarely, 0.15 above it). The
  // per-sample spread is ~0.05 (measured), so the mean of 8 × 8 pixels at 256 samples has σ ≈ 4e-4:
  // 3e-3 is about seven of those. One pixel at 16 samples, as this test read before, is ±5 %.
  for (float deg : {20.0f, 60.0f, 75.0f}) {
    const float theta = glm::radians(deg), w = std::pow(1.0f - std::cos(theta), 5.0f);
    const Image im = view_horizontal_surface(m, theta, false, env, 256);
    for (int c = 0; c < 3; ++c) {
      const float expected = m.base_color[c] + (1.0f - m.base_color[c]) * w;
      EXPECT_NEAR(image_mean(im, c), expected, 3e-3f) << deg << "° channel " << c;
    }
  }
}

// A smooth thin dielectric slab (KHR_materials_transmission 1, ior 1.5): seen from above it
// reflects the sky with F = F0 + (1 − F0)(1 − cosθ)^5, F0 = ((ior − 1)/(ior + 1))² = 0.04; seen from
// below, the sky comes through with 1 − F.
TEST(Integrator, DielectricSlabAgainstFresnel) {
  test::TempDir dir;
  const std::string env = sky_ground_env(dir);
  MaterialDesc m;
  m.base_color = Rgb(1.0f);
  m.metallic = 0.0f;
  m.roughness = 0.0f;
  m.transmission = 1.0f;
  m.ior = 1.5f;
  // Each path picks reflection or transmission with probability ∝ its weight, so a sample is 0 or
  // 1 here: the mean of n = 8·8·4096 samples has σ = sqrt(F(1 − F)/n) ≤ 1e-3; 3e-3 is three of those.
  for (float deg : {0.0f, 45.0f, 70.0f}) {
    const float theta = glm::radians(deg);
    const float F = 0.04f + 0.96f * std::pow(1.0f - std::cos(theta), 5.0f);
    EXPECT_NEAR(image_mean(view_horizontal_surface(m, theta, false, env, 4096), 0), F, 3e-3f) << deg;
    EXPECT_NEAR(image_mean(view_horizontal_surface(m, theta, true, env, 4096), 0), 1.0f - F, 3e-3f) << deg;
  }
}

// The three ways of sampling the environment estimate the same integral.
TEST(Integrator, MisNeeAndBsdfSamplingAgree) {
  test::TempDir dir;
  // A sky with a broad bright region (radiance 0.2 to 6.2), so that every strategy has work to do
  // but none has heavy tails that need millions of samples.
  Image env(32, 16, 3);
  const glm::vec3 bright = glm::normalize(glm::vec3(0.6f, 0.7f, 0.4f));
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 32; ++i) {
      const float th = kPiF * (j + 0.5f) / 16.0f, ph = (float(i) + 0.5f) / 32.0f * 2.0f * kPiF - kPiF;
      const glm::vec3 d(std::sin(th) * std::sin(ph), std::cos(th), -std::sin(th) * std::cos(ph));
      const float v = 0.2f + 6.0f * std::pow(std::max(0.0f, glm::dot(d, bright)), 4.0f);
      for (int c = 0; c < 3; ++c) env.at(i, j, c) = v;
    }
  write_image(dir.path() / "env.exr", env, PixelFormat::float32);
  auto make = [&] {
    Scene s;
    MaterialDesc glossy;
    glossy.base_color = Rgb(0.9f, 0.7f, 0.5f);
    glossy.metallic = 1.0f;
    glossy.roughness = 0.5f;
    s.materials.push_back(glossy);
    s.materials.push_back(lambertian(Rgb(0.5f)));
    add_sphere(s, 0, 1.0f, 24, 48);
    add_quad(s, 1, glm::translate(glm::dmat4(1.0), glm::dvec3(0, -1, 0)) *
                       glm::rotate(glm::dmat4(1.0), glm::radians(-90.0), glm::dvec3(1, 0, 0)), 8.0f);
    s.cameras.push_back(test::perspective_camera({0, 1, 4}, {0, -0.2f, 0}, 45.0f));
    return s;
  };
  SceneSetup setup;
  setup.width = setup.height = 24;
  setup.env = (dir.path() / "env.exr").string();
  const int spp = 1024;
  // Each strategy rendered twice, with other seeds: the pair's mean is its estimate, their
  // difference its noise (per pixel, D² has expectation 2σ²), so the agreement asked for below is
  // in units of the measured noise rather than a fixed share that one random layout may exceed.
  Image img[3][2];
  const LightSampling modes[3] = {LightSampling::mis, LightSampling::nee, LightSampling::bsdf};
  for (int k = 0; k < 3; ++k) {
    IntegratorSettings is;
    is.light_sampling = modes[k];
    is.max_depth = 4;
    for (int r = 0; r < 2; ++r) img[k][r] = render_scene(make(), setup, spp, is, 0, 100 + 10 * r + k).radiance();
  }
  // Over 6×6-pixel blocks: the block mean of each strategy and its variance, Σ D²/(4·36²).
  auto block = [&](int k, int bx, int by, double& mean, double& var) {
    mean = var = 0;
    for (int y = by * 6; y < by * 6 + 6; ++y)
      for (int x = bx * 6; x < bx * 6 + 6; ++x) {
        const double a = pixel(img[k][0], x, y).y, b = pixel(img[k][1], x, y).y;
        mean += 0.5 * (a + b) / 36.0;
        var += (a - b) * (a - b) / (4.0 * 36.0 * 36.0);
      }
  };
  // 32 comparisons at 4.5σ, σ estimated from 36 pixel pairs (Student's t, 36 degrees of freedom): a
  // false alarm about once in 500 layouts of the random numbers; a bias of 2 % (a strategy's weight
  // or pdf off by that) exceeds it in the blocks where the noise is least.
  double worst_sigma = 0;
  for (int by = 0; by < 4; ++by)
    for (int bx = 0; bx < 4; ++bx) {
      double m[3], v[3];
      for (int k = 0; k < 3; ++k) block(k, bx, by, m[k], v[k]);
      for (int k = 1; k < 3; ++k) {
        const double sigma = std::sqrt(v[0] + v[k]);
        worst_sigma = std::max(worst_sigma, sigma / m[0]);
        // (Blocks of sky seen directly are noiseless and equal under every strategy: σ = 0 there.)
        EXPECT_NEAR(m[k], m[0], 4.5 * sigma + 1e-6 * m[0]) << (k == 1 ? "NEE" : "BSDF") << " vs MIS, block " << bx << "," << by
                                               << ": σ " << sigma / m[0] << " of the mean";
      }
    }
  // The test can tell: the noise it allows stays within a few percent of the mean (measured: at most
  // 1.0 %, so 4.5σ ≤ 4.5 % in the worst block and about 2 % in most).
  EXPECT_LT(worst_sigma, 0.015);
  double total[3] = {0, 0, 0};
  for (int k = 0; k < 3; ++k)
    for (int y = 0; y < 24; ++y)
      for (int x = 0; x < 24; ++x) total[k] += pixel(img[k][0], x, y).y + pixel(img[k][1], x, y).y;
  EXPECT_NEAR(total[1], total[0], 0.01 * total[0]);
  EXPECT_NEAR(total[2], total[0], 0.01 * total[0]);
}

// Every sample is seeded by (seed, pixel, index): the image is bit-identical for any thread count.
TEST(Integrator, DeterministicAcrossThreadCounts) {
  auto make = [] {
    Scene s;
    MaterialDesc blend = lambertian(Rgb(0.3f, 0.6f, 0.9f));
    blend.alpha_mode = AlphaMode::blend;
    blend.base_alpha = 0.5f;
    s.materials.push_back(blend);
    add_sphere(s, 0, 1.0f, 12, 24);
    s.cameras.push_back(test::perspective_camera({0, 0, 3}, {0, 0, 0}, 50.0f));
    return s;
  };
  SceneSetup setup;
  setup.width = 40, setup.height = 30;
  const Film a = render_scene(make(), setup, 8, {}, 1);
  const Film b = render_scene(make(), setup, 8, {}, 2);
  ASSERT_EQ(a.radiance_sum.size(), b.radiance_sum.size());
  EXPECT_EQ(std::memcmp(a.radiance_sum.data(), b.radiance_sum.data(), a.radiance_sum.size() * sizeof(glm::dvec3)), 0);
  const Film c = render_scene(make(), setup, 8, {}, 2, 8);
  EXPECT_NE(std::memcmp(a.radiance_sum.data(), c.radiance_sum.data(), a.radiance_sum.size() * sizeof(glm::dvec3)), 0)
      << "another seed gives another image";

  // Each pixel alone, from its samples' generators (renderer.h, pixel_rng: the film jitter first, then
  // the path), sums to the rendered pixel bit for bit: a pixel can be traced on its own to debug it.
  const PreparedScene prepared(make(), setup);
  RenderOptions o;
  o.spp = 8, o.seed = 7, o.aovs = false;
  const Film f = render(prepared.world(), o);
  IntegratorSettings integ = o.integrator;
  integ.aovs = false;
  integ.footprint_scale = resolve_footprint_scale(0.0f, 8);  // what render() resolves 0 to
  int differ = 0;
  for (int y = 0; y < setup.height; ++y)
    for (int x = 0; x < setup.width; ++x) {
      glm::dvec3 sum(0.0);
      for (std::uint32_t s = 0; s < 8; ++s) {
        Rng rng = pixel_rng(o.seed, x, y, setup.width, s);
        const float jx = rng.next_float(), jy = rng.next_float();
        sum += glm::dvec3(trace_path(prepared.world(), integ, float(x) + jx, float(y) + jy, rng).radiance);
      }
      differ += std::memcmp(&sum, &f.radiance_sum[std::size_t(y) * setup.width + x], sizeof sum) != 0;
    }
  EXPECT_EQ(differ, 0) << "of " << setup.width * setup.height << " pixels";
}

// An unlit quad textured with a 2×2 image (or 2×1 with alpha), filling an orthographic view exactly.
Image render_textured_quad(Image texture, const TextureTransform& transform, AlphaMode mode, const std::string& env) {
  Scene s;
  ImageDesc im;
  im.pixels = std::move(texture);
  im.where = "images[0]";
  s.images.push_back(std::move(im));
  TextureDesc t;
  t.image = 0;
  t.sampler.wrap_s = t.sampler.wrap_t = WrapMode::clamp_to_edge;
  s.textures.push_back(t);
  MaterialDesc m;
  m.unlit = true;
  m.base_color_texture.texture = 0;
  m.base_color_texture.transform = transform;
  m.alpha_mode = mode;
  m.alpha_cutoff = 0.5f;
  s.materials.push_back(m);
  add_quad(s, 0, glm::dmat4(1.0), 2.0f);
  s.cameras.push_back(ortho_camera({0, 0, 5}, {0, 0, 0}, 1.0f));
  SceneSetup setup;
  setup.width = setup.height = 8;
  setup.env = env;
  return render_scene(std::move(s), setup, 4).radiance();
}

// alphaMode MASK: the left texel's alpha 0.2 is below the cutoff 0.5 (the environment shows
// through); the right texel's 0.9 is above (the texture's color shows).
TEST(Integrator, MaskCutoffAtKnownPixels) {
  Image tex(2, 1, 4);
  const float texels[8] = {1, 0, 0, 0.2f, 0, 0, 1, 0.9f};
  std::copy(texels, texels + 8, tex.pixels.begin());
  const Image im = render_textured_quad(tex, {}, AlphaMode::mask, "0,1,0");
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) {
      const glm::vec3 expected = x < 4 ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
      EXPECT_EQ(pixel(im, x, y), expected) << x << "," << y;
    }
}

// KHR_texture_transform: with rotation π/2 and offset (0, 1), uv ↦ (v, 1 − u) (u' = cos·u + sin·v,
// v' = −sin·u + cos·v, then the offset), so each quadrant shows the texel rotated into it.
TEST(Integrator, TextureTransformAtKnownPixels) {
  Image tex(2, 2, 3);
  const glm::vec3 red(1, 0, 0), green(0, 1, 0), blue(0, 0, 1), white(1, 1, 1);
  const glm::vec3 texels[4] = {red, green, blue, white};  // rows from the top: red green / blue white
  for (int k = 0; k < 4; ++k)
    for (int c = 0; c < 3; ++c) tex.pixels[std::size_t(k) * 3 + c] = texels[k][c];
  const Image plain = render_textured_quad(tex, {}, AlphaMode::opaque, "0,0,0");
  EXPECT_EQ(pixel(plain, 1, 1), red);
  EXPECT_EQ(pixel(plain, 6, 1), green);
  EXPECT_EQ(pixel(plain, 1, 6), blue);
  EXPECT_EQ(pixel(plain, 6, 6), white);
  const Image turned =
      render_textured_quad(tex, TextureTransform::make({0.0f, 1.0f}, kPiF / 2, {1.0f, 1.0f}), AlphaMode::opaque, "0,0,0");
  // Top-left quadrant uv ≈ (.25, .25) → (.25, .75): the bottom-left texel; and so on.
  EXPECT_EQ(pixel(turned, 1, 1), blue);
  EXPECT_EQ(pixel(turned, 6, 1), red);
  EXPECT_EQ(pixel(turned, 1, 6), white);
  EXPECT_EQ(pixel(turned, 6, 6), green);
}

// The BSDF: at the extensions' defaults it is the shared gltf_eval (appearance/gltf.h) exactly, and
// its sampler's weights are f·cos/pdf.
TEST(SurfaceBsdf, DefaultsAreTheGltfBrdf) {
  Rng rng(3, 5);
  for (float rough : {0.05f, 0.3f, 0.8f})
    for (float metal : {0.0f, 0.4f, 1.0f}) {
      ShadingParams p;
      p.base_color = Rgb(0.7f, 0.4f, 0.2f);
      p.roughness = rough;
      p.metallic = metal;
      const SurfaceBsdf bsdf(p);
      const GltfParams g{p.base_color, metal, rough};
      for (int k = 0; k < 200; ++k) {
        const glm::vec3 wi = glm::normalize(glm::vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float()));
        const glm::vec3 wo = glm::normalize(glm::vec3(rng.next_float() - 0.5f, rng.next_float() - 0.5f, rng.next_float()));
        const Rgb a = bsdf.eval(wi, wo), b = gltf_eval(g, wi, wo);
        for (int c = 0; c < 3; ++c) ASSERT_NEAR(a[c], b[c], 1e-4f * std::max(1.0f, b[c])) << rough << " " << metal;
        const BsdfSample s = bsdf.sample(wo, SampleU(rng.next_float(), rng.next_float(), rng.next_float()));
        if (s.kind != SampleKind::finite) continue;
        EXPECT_NEAR(s.pdf, bsdf.pdf(s.wi, wo), 1e-4f * s.pdf);
        const Rgb expected = bsdf.eval(s.wi, wo) * (s.wi.z / s.pdf);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], expected[c], 1e-4f * std::max(1.0f, expected[c]));
      }
    }
}

// The sampling density integrates to the probability that sample() returns a finite direction
// (visible-normal reflections that point below the horizon are absorbed, so it is a little under 1).
TEST(SurfaceBsdf, PdfIntegratesToOne) {
  ShadingParams p;
  p.base_color = Rgb(0.5f);
  p.roughness = 0.4f;
  p.metallic = 0.3f;
  const SurfaceBsdf bsdf(p);
  const glm::vec3 wo = glm::normalize(glm::vec3(0.5f, 0.1f, 0.8f));
  Rng rng(11, 1);
  const int n = 1000000;
  double sum = 0.0;
  int finite = 0;
  for (int k = 0; k < n; ++k) {
    // Uniform hemisphere, density 1/(2π).
    const float z = rng.next_float(), phi = 2.0f * kPiF * rng.next_float(), r = std::sqrt(1.0f - z * z);
    sum += bsdf.pdf({r * std::cos(phi), r * std::sin(phi), z}, wo) * 2.0 * kPiF;
    finite += bsdf.sample(wo, SampleU(rng.next_float(), rng.next_float(), rng.next_float())).kind == SampleKind::finite;
  }
  EXPECT_LT(double(finite) / n, 1.0);
  EXPECT_NEAR(sum / n, double(finite) / n, 0.01);
}

// EON (KHR_materials_diffuse_roughness) preserves energy: white EON's directional albedo is 1.
TEST(SurfaceBsdf, EonWhiteFurnace) {
  for (float r : {0.3f, 1.0f})
    for (float theta : {0.0f, 45.0f, 80.0f}) {
      const glm::vec3 wo(std::sin(glm::radians(theta)), 0.0f, std::cos(glm::radians(theta)));
      Rng rng(2, 9);
      const int n = 200000;
      double sum = 0.0;
      for (int k = 0; k < n; ++k) {
        const float z = rng.next_float(), phi = 2.0f * kPiF * rng.next_float(), s = std::sqrt(1.0f - z * z);
        const glm::vec3 wi(s * std::cos(phi), s * std::sin(phi), z);
        sum += eon_eval(Rgb(1.0f), r, wi, wo).x * z * 2.0 * kPiF;
      }
      // The fitted albedo is good to 0.1 %; the Monte Carlo error here is ~0.3 %.
      EXPECT_NEAR(sum / n, 1.0, 0.012) << "r " << r << " θ " << theta;
    }
}

}  // namespace
}  // namespace svbrdf

namespace svbrdf {
namespace {

// The equirectangular environment's sampler: E[L(ω)/p(ω)] is ∫ L dω, which for a piecewise-constant
// image is exactly Σ L_ij·ΔΩ_ij with ΔΩ_ij = (2π/W)·(cos θ_j − cos θ_{j+1}); and p integrates to 1.
TEST(Environment, ImportanceSamplingIsUnbiased) {
  Image im(8, 4, 3);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 8; ++i)
      for (int c = 0; c < 3; ++c) im.at(i, j, c) = 0.1f + float((i * 7 + j * 3 + c) % 5) * (j == 1 && i == 2 ? 20.0f : 1.0f);
  const Environment env = Environment::from_image(im, "test");
  double exact = 0.0;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 8; ++i)
      exact += im.at(i, j, 1) * (2.0 * kPiF / 8.0) * (std::cos(kPiF * j / 4.0) - std::cos(kPiF * (j + 1) / 4.0));
  Rng rng(5, 5);
  const int n = 400000;
  double est = 0.0, pdf_integral = 0.0;
  for (int k = 0; k < n; ++k) {
    float pdf = 0.0f;
    const glm::vec3 d = env.sample({rng.next_float(), rng.next_float(), rng.next_float()}, pdf);
    ASSERT_GT(pdf, 0.0f);
    EXPECT_NEAR(pdf, env.pdf(d), 1e-3f * pdf);
    est += env.radiance(d).y / pdf;
    // ∫ p dω by uniform sphere sampling.
    const float z = 1.0f - 2.0f * rng.next_float(), phi = 2.0f * kPiF * rng.next_float(), r = std::sqrt(1.0f - z * z);
    pdf_integral += env.pdf({r * std::cos(phi), z, r * std::sin(phi)}) * 4.0 * kPiF;
  }
  EXPECT_NEAR(est / n, exact, 0.002 * exact);
  EXPECT_NEAR(pdf_integral / n, 1.0, 0.02);
}

// Ray differentials: an orthographic camera of half height 1 over W pixels sees a 2-unit quad whose
// uv spans [0, 1], so one pixel step moves uv by 1/W and a base color texture of N texels has a
// footprint of N/W texels: the MIP-level AOV reads log2(N/W).
TEST(Integrator, CameraFootprintGivesTheMipLevel) {
  Scene s;
  MaterialDesc m = lambertian(Rgb(1.0f));
  m.base_color_texture.texture = test::add_image_texture(s, Image(256, 256, 3));
  s.materials.push_back(m);
  add_quad(s, 0, glm::dmat4(1.0), 2.0f);
  s.cameras.push_back(ortho_camera({0, 0, 5}, {0, 0, 0}, 1.0f));
  SceneSetup setup;
  setup.width = setup.height = 16;
  const Image level = render_scene(std::move(s), setup, 1).mip_level();
  // 256 texels over 16 pixels: 16 texels per pixel, level 4.
  EXPECT_NEAR(level.at(8, 8, 0), 4.0f, 1e-4f);
  EXPECT_NEAR(level.at(2, 13, 0), 4.0f, 1e-4f);
}

// Perspective: at distance d along the axis, a pixel spans 2·d·tan(fov/2)/H; the approximation used
// for secondary rays (pbrt-v4's, from the camera) agrees with the exact camera differential there.
TEST(Camera, DifferentialsAtKnownDistance) {
  const CameraDesc desc = test::perspective_camera({0, 0, 4}, {0, 0, 0}, 60.0f);
  const Camera cam(desc, 200, 100);
  const CameraRay cr = cam.generate(100.0f, 50.0f);
  const glm::vec3 n(0, 0, 1);
  auto on_plane = [&](const glm::vec3& o, const glm::vec3& d) { return o + d * (-o.z / d.z); };
  const glm::vec3 p = on_plane(cr.ray.origin, cr.ray.dir);
  const glm::vec3 dpdx = on_plane(cr.dx_origin, cr.dx_dir) - p, dpdy = on_plane(cr.dy_origin, cr.dy_dir) - p;
  const float pixel = 2.0f * 4.0f * std::tan(glm::radians(30.0f)) / 100.0f;
  EXPECT_NEAR(dpdx.x, pixel, 1e-3f * pixel);
  EXPECT_NEAR(dpdy.y, -pixel, 1e-3f * pixel);
  glm::vec3 ax, ay;
  cam.approximate_dp(p, n, ax, ay);
  EXPECT_NEAR(glm::length(ax - dpdx), 0.0f, 1e-3f * pixel);
  EXPECT_NEAR(glm::length(ay - dpdy), 0.0f, 1e-3f * pixel);
}

// The footprint scale of a render: each sample's share of the pixel, 1/√spp, unless given — with no
// floor, unlike pbrt-v4's max(1/8, 1/√spp) (renderer.h says why).
TEST(Renderer, FootprintScaleIsTheSamplesShareOfThePixelUnlessGiven) {
  EXPECT_FLOAT_EQ(resolve_footprint_scale(0.0f, 1), 1.0f);
  EXPECT_FLOAT_EQ(resolve_footprint_scale(0.0f, 4), 0.5f);
  EXPECT_FLOAT_EQ(resolve_footprint_scale(0.0f, 16), 0.25f);
  EXPECT_FLOAT_EQ(resolve_footprint_scale(0.0f, 64), 0.125f);
  EXPECT_FLOAT_EQ(resolve_footprint_scale(0.0f, 256), 0.0625f);
  EXPECT_FLOAT_EQ(resolve_footprint_scale(0.0f, 4096), 0.015625f);
  EXPECT_FLOAT_EQ(resolve_footprint_scale(0.3f, 4096), 0.3f);
}

}  // namespace
}  // namespace svbrdf
