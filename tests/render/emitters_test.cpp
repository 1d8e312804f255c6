// Emissive triangles as lights, checked against Lambert's closed form for the irradiance from a
// uniformly emitting polygon, across the three light-sampling strategies.
#include <gtest/gtest.h>

#include <cmath>

#include "render/emitters.h"
#include "render_test_scenes.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

using test::add_quad;
using test::lambertian;
using test::ortho_camera;
using test::render_scene;

constexpr double kPi = 3.141592653589793;

// Irradiance at x (surface normal n) from a polygon of uniform radiance L seen entirely above the
// surface: Lambert's formula, E = L/2·|Σᵢ γᵢ·n·(rᵢ × rᵢ₊₁)/|rᵢ × rᵢ₊₁||, γᵢ the angle the edge subtends
// at x (Lambert 1760; Arvo, "Irradiance tensors", SIGGRAPH 1995, eq. 10).
double polygon_irradiance(const std::vector<glm::dvec3>& poly, const glm::dvec3& x, const glm::dvec3& n, double L) {
  double sum = 0.0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const glm::dvec3 a = glm::normalize(poly[i] - x), b = glm::normalize(poly[(i + 1) % poly.size()] - x);
    const glm::dvec3 c = glm::cross(a, b);
    sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, glm::normalize(c));
  }
  return 0.5 * L * std::abs(sum);
}

constexpr int kRes = 48;
constexpr float kHalf = 2.0f;        // the camera sees [−2, 2]² of the floor
constexpr double kHeight = 1.0;      // the panel's height above the floor
constexpr double kPanel = 1.0;       // its side
constexpr double kRho = 0.5;         // the floor's albedo
constexpr double kRadiance = 3.0;    // the panel's emitted radiance

// A Lambertian floor (side 8, z = 0, front +z) and a square emissive panel above it: facing down
// (front face −z) unless `up`, single- or double-sided. The camera looks straight down at the floor.
Scene panel_scene(bool up, bool double_sided) {
  Scene s;
  s.materials.push_back(lambertian(Rgb(float(kRho))));
  MaterialDesc panel = lambertian(Rgb(0.0f));
  panel.emissive = Rgb(1.0f);
  panel.emissive_strength = float(kRadiance);
  panel.double_sided = double_sided;
  s.materials.push_back(panel);
  add_quad(s, 0, glm::dmat4(1.0), 8.0f);
  glm::dmat4 m = glm::translate(glm::dmat4(1.0), glm::dvec3(0, 0, kHeight));
  if (!up) m = glm::rotate(m, kPi, glm::dvec3(1, 0, 0));
  add_quad(s, 1, m, float(kPanel));
  s.cameras.push_back(ortho_camera({0, 0, 5}, {0, 0, 0}, kHalf));
  return s;
}

// The closed form's mean over pixel (x, y) of the kRes² frame: ρ/π·E on a 4×4 grid of the pixel.
double expected_pixel(int x, int y) {
  const double h = kPanel / 2;
  const std::vector<glm::dvec3> poly = {{-h, -h, kHeight}, {h, -h, kHeight}, {h, h, kHeight}, {-h, h, kHeight}};
  double sum = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b) {
      const double px = -kHalf + 2.0 * kHalf * (x + (a + 0.5) / 4) / kRes;
      const double py = kHalf - 2.0 * kHalf * (y + (b + 0.5) / 4) / kRes;
      sum += kRho / kPi * polygon_irradiance(poly, {px, py, 0.0}, {0, 0, 1}, kRadiance);
    }
  return sum / 16;
}

struct Errors {
  double bias = 0;  // Σ(render − closed form) / Σ closed form over the floor pixels measured
  double mse = 0;   // mean squared error per pixel: the estimator's variance, the closed form being exact
};

// Renders direct light only (one scattering event: the panel's own surface adds nothing) under a
// strategy and measures it against the closed form, away from the panel's own image.
Errors measure(LightSampling strategy, int spp, bool up = false, bool double_sided = false) {
  SceneSetup setup;
  setup.width = setup.height = kRes;
  setup.env = "0,0,0";
  IntegratorSettings integ;
  integ.max_depth = 1;
  integ.light_sampling = strategy;
  const Image im = render_scene(panel_scene(up, double_sided), setup, spp, integ).radiance();
  Errors e;
  double sum_ref = 0;
  int n = 0;
  for (int y = 0; y < kRes; ++y)
    for (int x = 0; x < kRes; ++x) {
      // Skip the pixels the camera may see the panel in (a double-sided panel shows its back).
      const double cx = -kHalf + 2.0 * kHalf * (x + 0.5) / kRes, cy = kHalf - 2.0 * kHalf * (y + 0.5) / kRes;
      if (std::abs(cx) < kPanel / 2 + 0.1 && std::abs(cy) < kPanel / 2 + 0.1) continue;
      const double ref = expected_pixel(x, y), v = im.pixels[(std::size_t(y) * kRes + x) * im.channels];
      e.bias += v - ref;
      e.mse += (v - ref) * (v - ref);
      sum_ref += ref;
      ++n;
    }
  e.bias /= sum_ref;
  e.mse /= n;
  return e;
}

// The three strategies agree with Lambert's closed form, and light sampling earns its keep: at equal
// samples its variance is at least 10× lower than BSDF sampling's.
TEST(Emitters, PanelLightsFloorAsLambertsFormulaSays) {
  const Errors mis = measure(LightSampling::mis, 64), nee = measure(LightSampling::nee, 64),
               bsdf = measure(LightSampling::bsdf, 64);
  std::printf("bias mis %+.4f nee %+.4f bsdf %+.4f; mse mis %.3g nee %.3g bsdf %.3g\n", mis.bias, nee.bias, bsdf.bias,
              mis.mse, nee.mse, bsdf.mse);
  // Over ~2000 pixels of 64 samples the means' relative noise is well under 0.5 % for MIS and NEE;
  // BSDF sampling's is larger (its mse is) and gets 2 %.
  EXPECT_LT(std::abs(mis.bias), 0.005);
  EXPECT_LT(std::abs(nee.bias), 0.005);
  EXPECT_LT(std::abs(bsdf.bias), 0.02);
  EXPECT_GT(bsdf.mse, 10.0 * nee.mse);
  EXPECT_GT(bsdf.mse, 10.0 * mis.mse);
}

// A single-sided panel turned away emits nothing toward the floor; the same panel double-sided
// lights it as the panel facing it does.
TEST(Emitters, OnlyDoubleSidedEmittersLightFromTheirBack) {
  for (const LightSampling strategy : {LightSampling::mis, LightSampling::nee, LightSampling::bsdf}) {
    SCOPED_TRACE(int(strategy));
    const Errors away = measure(strategy, 8, /*up=*/true, /*double_sided=*/false);
    EXPECT_NEAR(away.bias, -1.0, 1e-9);  // every pixel black
    const Errors two_sided = measure(strategy, 64, /*up=*/true, /*double_sided=*/true);
    EXPECT_LT(std::abs(two_sided.bias), strategy == LightSampling::bsdf ? 0.02 : 0.005);
  }
}

// The choice by power: a panel twice as bright is drawn twice as often; nothing that does not emit
// is drawn; a hit's density matches the one sample() reports for the same point.
TEST(Emitters, ChosenByPowerWithMatchingDensity) {
  Scene s = panel_scene(false, false);
  MaterialDesc brighter = s.materials[1];
  brighter.emissive_strength *= 2.0f;
  s.materials.push_back(brighter);
  add_quad(s, 2, glm::translate(glm::dmat4(1.0), glm::dvec3(3, 0, kHeight)) * glm::rotate(glm::dmat4(1.0), kPi, glm::dvec3(1, 0, 0)),
           float(kPanel));
  SceneSetup setup;
  setup.width = setup.height = 4;
  const PreparedScene prepared(std::move(s), setup);
  const Emitters& e = prepared.emitters();
  ASSERT_EQ(e.triangle_count(), 4u);  // the two panels' triangles; the floor emits nothing
  EXPECT_NEAR(e.total_power(), kPi * kRadiance * kPanel * kPanel * 3.0, 1e-4);
  Rng rng(3, 0);
  int right = 0;
  const int n = 20000;
  const glm::vec3 x(1.5f, 0.2f, 0.0f);
  for (int i = 0; i < n; ++i) {
    const EmitterSample es = e.sample(x, {rng.next_float(), rng.next_float(), rng.next_float()});
    ASSERT_GT(es.pdf, 0.0f);
    const glm::vec3 p = x + es.wi * es.distance;
    right += p.x > 1.5f;
    // The ray from x toward the point hits it; pdf() of that hit is the density sample() gave.
    const RayHit hit = prepared.bvh().intersect(x + es.wi * 1e-4f, es.wi, 0.0f, 1e30f, 0);
    ASSERT_TRUE(hit.found());
    RayHit from_x = hit;
    from_x.t += 1e-4f;
    EXPECT_NEAR(e.pdf(from_x, es.wi), es.pdf, 1e-3f * es.pdf);
  }
  // Binomial: p = 2/3, σ = √(p(1−p)/n) ≈ 0.0033.
  EXPECT_NEAR(double(right) / n, 2.0 / 3.0, 0.015);
}

// --clamp caps what one indirect light sample brings back and leaves direct light alone: with the
// same random numbers, the clamped image lies between the direct-only image and the unclamped one,
// within two capped contributions per sample of the direct one (at depth 2 a path's indirect light is
// the emitter's light sample and the emission its BSDF sample finds, at its second hit: here a white
// wall beside the panel), and a cap above every sample changes nothing.
TEST(Emitters, ClampCapsIndirectSamplesOnly) {
  SceneSetup setup;
  setup.width = setup.height = 16;
  setup.env = "0,0,0";
  auto render_with = [&](int depth, float clamp) {
    IntegratorSettings integ;
    integ.max_depth = depth;
    integ.clamp = clamp;
    Scene s = panel_scene(false, false);
    // A white wall at x = 1, facing −x.
    s.materials.push_back(lambertian(Rgb(1.0f)));
    add_quad(s, 2, glm::translate(glm::dmat4(1.0), glm::dvec3(1, 0, 0)) * glm::rotate(glm::dmat4(1.0), -kPi / 2, glm::dvec3(0, 1, 0)),
             4.0f);
    return render_scene(std::move(s), setup, 16, integ).radiance();
  };
  const float c = 0.01f;
  const Image direct = render_with(1, 0.0f), full = render_with(2, 0.0f), clamped = render_with(2, c),
              loose = render_with(2, 1e30f);
  int capped = 0;
  for (std::size_t i = 0; i < full.pixels.size(); ++i) {
    EXPECT_LE(clamped.pixels[i], full.pixels[i] * (1.0f + 1e-5f));
    EXPECT_GE(clamped.pixels[i], direct.pixels[i] * (1.0f - 1e-5f));
    EXPECT_LE(clamped.pixels[i] - direct.pixels[i], 2.0f * c * (1.0f + 1e-5f));
    EXPECT_EQ(loose.pixels[i], full.pixels[i]);
    capped += clamped.pixels[i] < full.pixels[i] * (1.0f - 1e-3f);
  }
  EXPECT_GT(capped, 0);  // the cap was low enough to act
}

}  // namespace
}  // namespace svbrdf
