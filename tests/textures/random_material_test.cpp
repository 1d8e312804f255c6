// The random material family (textures/random_material.h) against the distributions its header
// states: determinism per seed, the roughness range over seeds, the tilt bounds, one-axis
// corrugations, that a two-population texture holds two populations and nothing much between, and the
// sheen's and the transmission's share of the seeds, ranges and coverage, and that the transmission's
// stream leaves every other ingredient's draw as it was.
#include "textures/random_material.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>

namespace svbrdf {
namespace {

constexpr int kSeeds = 200;
constexpr double kDeg = 3.14159265358979323846 / 180.0;

double tilt_deg(const glm::vec3& n) { return std::acos(std::clamp(double(n.z), -1.0, 1.0)) / kDeg; }

template <class Pred>
double fraction(const MaterialTexels& t, Pred pred) {
  std::size_t n = 0;
  for (std::size_t k = 0; k < t.size(); ++k) n += pred(k) ? 1 : 0;
  return double(n) / double(t.size());
}

bool same(const MaterialTexels& a, const MaterialTexels& b) {
  return a.base_color == b.base_color && a.metallic == b.metallic && a.roughness == b.roughness && a.normal == b.normal &&
         a.transmission == b.transmission && a.transmission_factor == b.transmission_factor;
}

TEST(RandomMaterial, SameSeedSameTexelsAtAnyThreadCount) {
  for (std::uint64_t seed : {1u, 7u, 12345u}) {
    const RandomMaterialDraw d = draw_random_material(seed);
    const MaterialTexels a = random_material_texels(d, 64);
    MaterialTexels b;
    tbb::task_arena one(1);
    one.execute([&] { b = random_material_texels(draw_random_material(seed), 64); });
    EXPECT_TRUE(same(a, b)) << seed;
    EXPECT_EQ(d.summary(), draw_random_material(seed).summary());
    EXPECT_FALSE(same(a, random_material_texels(draw_random_material(seed + 1), 64))) << seed;
  }
}

// Perceptual roughness stays in [0.02, 1] and the seeds reach both ends; the base population is
// log-uniform, so P(r1 < 0.1) = ln(0.1/0.02)/ln(1/0.02) = 0.41 (±0.035 for 200 seeds).
TEST(RandomMaterial, RoughnessSpansItsRange) {
  float lo = 1, hi = 0;
  int below = 0, single = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const RandomMaterialDraw d = draw_random_material(seed);
    const MaterialTexels t = random_material_texels(d, 32);
    for (float r : t.roughness) {
      ASSERT_GE(r, 0.02f);
      ASSERT_LE(r, 1.0f);
      lo = std::min(lo, r), hi = std::max(hi, r);
    }
    if (d.second_share > 0) continue;
    // One population: its median texel is r1 within its ±15 % variation.
    std::vector<float> r = t.roughness;
    std::nth_element(r.begin(), r.begin() + std::ptrdiff_t(r.size() / 2), r.end());
    ++single;
    below += r[r.size() / 2] < 0.1f;
  }
  EXPECT_LE(lo, 0.021f);
  EXPECT_GE(hi, 0.95f);
  EXPECT_NEAR(double(below) / single, 0.411, 0.12);  // 3 deviations for the ~100 one-population seeds
}

// No texel tilts past 35°; a seed with relief tilts its steepest texel by what it drew, a flat one
// not at all; over the seeds the tilt reaches its bound.
TEST(RandomMaterial, TiltsWithinTheStatedBounds) {
  double steepest = 0;
  int flat = 0, partial = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const RandomMaterialDraw d = draw_random_material(seed);
    const MaterialTexels t = random_material_texels(d, 32);
    double most = 0;
    for (const glm::vec3& n : t.normal) most = std::max(most, tilt_deg(n));
    ASSERT_LE(most, 35.0 + 1e-2) << d.summary();
    steepest = std::max(steepest, most);
    if (d.relief == Relief::flat) {
      ++flat;
      EXPECT_EQ(most, 0.0) << d.summary();
      continue;
    }
    EXPECT_NEAR(most, d.max_tilt_deg, 0.05) << d.summary();
    if (d.relief_share < 1.0f) {
      // Where the relief is not, the surface is flat: the unrelieved share less half the mask's
      // edge (a fifth of the texels) is untilted but for the texels whose central differences
      // reach across its border (a ring that takes up to half of a small flat share at 32²).
      ++partial;
      EXPECT_GE(fraction(t, [&](std::size_t k) { return tilt_deg(t.normal[k]) < 1e-3; }), 0.25 * (0.9 - d.relief_share))
          << d.summary();
    }
  }
  EXPECT_GE(steepest, 33.0);
  // Flat is drawn with p = 0.15, partial relief with 0.5 of the rest (3 deviations for 200 seeds).
  EXPECT_NEAR(flat / double(kSeeds), 0.15, 0.08);
  EXPECT_NEAR(partial / double(kSeeds - flat), 0.5, 0.12);
}

// A corrugation varies along its axis only: the normal leans along the axis (a, b) of texel columns
// and rows, which in the tangent frame (+Y up, rows down) is (a, −b), so n.x·b + n.y·a = 0.
TEST(RandomMaterial, CorrugationsTiltAlongOneAxis) {
  int checked = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const RandomMaterialDraw d = draw_random_material(seed);
    if ((d.relief != Relief::ribbed && d.relief != Relief::brushed) || d.relief_share < 1.0f) continue;
    const MaterialTexels t = random_material_texels(d, 32);
    const glm::ivec2 a = d.corrugation_axis;
    double across = 0, along = 0;
    for (const glm::vec3& n : t.normal) {
      across = std::max(across, double(std::abs(n.x * float(a.y) + n.y * float(a.x))));
      along = std::max(along, double(std::abs(n.x * float(a.x) - n.y * float(a.y))));
    }
    EXPECT_LT(across, 1e-5) << d.summary();
    EXPECT_GT(along, 0.05) << d.summary();
    ++checked;
  }
  EXPECT_GE(checked, 10);
}

// A two-population texture: texels within ±20 % (in ln r, more than the ±15 % variation) of r1 and
// of r2 in the drawn shares, the two ≥ 2.5× apart, and at most a few percent in between (the edges).
TEST(RandomMaterial, TwoPopulationsAreTwo) {
  int two = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const RandomMaterialDraw d = draw_random_material(seed);
    if (d.second_share == 0) continue;
    ++two;
    const MaterialTexels t = random_material_texels(d, 64);
    const double r1 = d.roughness, r2 = d.second_roughness;
    ASSERT_GE(std::max(r1, r2) / std::min(r1, r2), 2.5 - 1e-6) << d.summary();
    auto near = [&](double r, double of) { return std::abs(std::log(std::clamp(r, 0.02, 1.0) / std::clamp(of, 0.02, 1.0))) < 0.2; };
    const double first = fraction(t, [&](std::size_t k) { return near(t.roughness[k], r1); });
    const double second = fraction(t, [&](std::size_t k) { return near(t.roughness[k], r2); });
    EXPECT_NEAR(second, d.second_share, 0.06) << d.summary();
    EXPECT_NEAR(first, 1 - d.second_share, 0.06) << d.summary();
    EXPECT_GE(first + second, 0.94) << d.summary();
  }
  EXPECT_NEAR(two / double(kSeeds), 0.5, 0.12);
}

// Metal, dielectric or both in the drawn share; colours within [0, 1].
TEST(RandomMaterial, MetalAndColour) {
  int both = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const RandomMaterialDraw d = draw_random_material(seed);
    const MaterialTexels t = random_material_texels(d, 32);
    const double metal = fraction(t, [&](std::size_t k) { return t.metallic[k] > 0.5f; });
    for (const glm::vec3& c : t.base_color)
      for (int i = 0; i < 3; ++i) ASSERT_TRUE(c[i] >= 0 && c[i] <= 1) << d.summary();
    switch (d.metal) {
      case MetalMix::dielectric: EXPECT_EQ(metal, 0.0); break;
      case MetalMix::metal: EXPECT_EQ(metal, 1.0); break;
      case MetalMix::both:
        ++both;
        EXPECT_NEAR(metal, d.metal_share, 0.06) << d.summary();
        break;
    }
  }
  EXPECT_NEAR(both / double(kSeeds), 0.3, 0.1);
}

// A third of the seeds draw a sheen, within the stated ranges (colour value 0.2–1, saturation ≤ 0.6,
// roughness 0.1–1); half of those are textured, covering their stated share of the texels (the mask's
// sharp edge: ±0.06 at 32²) with no sheen elsewhere, the rest hold their factors everywhere.
TEST(RandomMaterial, SheenOnAThirdOfTheSeeds) {
  int sheened = 0, textured = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const RandomMaterialDraw d = draw_random_material(seed);
    const MaterialTexels t = random_material_texels(d, 32);
    if (d.sheen_color == glm::vec3(0.0f)) {
      EXPECT_FALSE(t.has_sheen()) << d.summary();
      continue;
    }
    ++sheened;
    ASSERT_TRUE(t.has_sheen()) << d.summary();
    const float hi = std::max(d.sheen_color.r, std::max(d.sheen_color.g, d.sheen_color.b));
    const float lo = std::min(d.sheen_color.r, std::min(d.sheen_color.g, d.sheen_color.b));
    EXPECT_GE(hi, 0.2f - 1e-6f) << d.summary();
    EXPECT_LE(hi, 1.0f) << d.summary();
    EXPECT_GE(lo, hi * (1.0f - 0.6f) - 1e-6f) << d.summary();
    EXPECT_GE(d.sheen_roughness, 0.1f);
    EXPECT_LE(d.sheen_roughness, 1.0f);
    if (!d.sheen_textured) {
      EXPECT_TRUE(t.sheen_color.empty() && t.sheen_roughness.empty()) << d.summary();
      continue;
    }
    ++textured;
    const double covered = fraction(t, [&](std::size_t k) { return t.sheen_color[k].r + t.sheen_color[k].g + t.sheen_color[k].b > 0.5f * (d.sheen_color.r + d.sheen_color.g + d.sheen_color.b); });
    EXPECT_NEAR(covered, d.sheen_share, 0.06) << d.summary();
    for (std::size_t k = 0; k < t.size(); ++k)
      ASSERT_NEAR(t.sheen_roughness[k], d.sheen_roughness, 1.5f * d.sheen_roughness_variation * d.sheen_roughness + 1e-6f) << d.summary();  // noise of range about ±1
  }
  EXPECT_NEAR(sheened / double(kSeeds), 1.0 / 3.0, 0.1);
  EXPECT_NEAR(textured / double(std::max(1, sheened)), 0.5, 0.15);
}

// A quarter of the seeds with a dielectric part draw a transmission, with factor in [0.2, 1]; an
// all-metal seed none (the model transmits (1 − m) of it). Half of those are textured: the factor on
// the stated share of the texels (the mask's sharp edge: ±0.06 at 32²), nothing elsewhere and nothing
// between but on the edge; the rest hold the factor everywhere.
TEST(RandomMaterial, TransmissionOnAQuarterOfTheDielectricSeeds) {
  int dielectric = 0, transmitting = 0, textured = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const RandomMaterialDraw d = draw_random_material(seed);
    const MaterialTexels t = random_material_texels(d, 32);
    if (d.metal != MetalMix::metal) ++dielectric;
    if (d.transmission == 0.0f) {
      EXPECT_FALSE(t.has_transmission()) << d.summary();
      continue;
    }
    ++transmitting;
    EXPECT_NE(d.metal, MetalMix::metal) << d.summary();
    EXPECT_GE(d.transmission, 0.2f) << d.summary();
    EXPECT_LE(d.transmission, 1.0f) << d.summary();
    ASSERT_TRUE(t.has_transmission()) << d.summary();
    EXPECT_EQ(t.transmission_factor, d.transmission) << d.summary();
    if (!d.transmission_textured) {
      EXPECT_TRUE(t.transmission.empty()) << d.summary();
      continue;
    }
    ++textured;
    ASSERT_EQ(t.transmission.size(), t.size());
    for (float v : t.transmission) ASSERT_TRUE(v >= 0.0f && v <= d.transmission) << d.summary();
    const double full = fraction(t, [&](std::size_t k) { return t.transmission[k] == d.transmission; });
    const double none = fraction(t, [&](std::size_t k) { return t.transmission[k] == 0.0f; });
    EXPECT_NEAR(full, d.transmission_share, 0.06) << d.summary();
    EXPECT_GE(full + none, 0.94) << d.summary();
  }
  // 3 deviations: ~130 seeds with a dielectric part, ~33 transmitting.
  EXPECT_NEAR(transmitting / double(dielectric), 0.25, 0.12);
  EXPECT_NEAR(textured / double(std::max(1, transmitting)), 0.5, 0.26);
}

// The transmission draws from a stream of its own, so every other ingredient of every seed is as it
// was before the family drew transmissions: the summaries of seeds 1–200 without their transmission
// hash (FNV-1a, 64 bits, each line ending in a newline) to what the family printed before the stream
// existed (`svbrdf-bake random-family --seeds 200 --size 2`, the lines' text), and a seed's texels but
// the transmission are those of its draw without one.
TEST(RandomMaterial, TransmissionLeavesTheOtherIngredientsAsTheyWere) {
  std::uint64_t hash = 0xcbf29ce484222325u;
  int transmitting = 0;
  for (std::uint64_t seed = 1; seed <= kSeeds; ++seed) {
    const RandomMaterialDraw d = draw_random_material(seed);
    RandomMaterialDraw without = d;
    without.transmission = 0.0f;
    without.transmission_textured = false;
    without.transmission_share = 1.0f;
    without.transmission_feature = 0.0f;
    for (const char c : without.summary() + "\n") hash = (hash ^ std::uint8_t(c)) * 0x100000001b3u;
    if (d.transmission == 0.0f) continue;
    ++transmitting;
    MaterialTexels a = random_material_texels(d, 32);
    const MaterialTexels b = random_material_texels(without, 32);
    EXPECT_TRUE(a.has_transmission());
    a.transmission.clear();
    a.transmission_factor = 0.0f;
    EXPECT_TRUE(same(a, b)) << d.summary();
    EXPECT_TRUE(a.sheen_color == b.sheen_color && a.sheen_roughness == b.sheen_roughness &&
                a.sheen_color_factor == b.sheen_color_factor && a.anisotropy == b.anisotropy &&
                a.anisotropy_direction == b.anisotropy_direction && a.anisotropy_factor == b.anisotropy_factor)
        << d.summary();
  }
  EXPECT_EQ(hash, 0xc88012c149a9b3b6u);
  EXPECT_GT(transmitting, 0);
}

}  // namespace
}  // namespace svbrdf
