// A lobe's normal as the MIP file stores it (stored_normal.h): close to the normal it codes, and a
// fixed point of encoding what it decodes to, which the file's bit-identical round trip rests on.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include "mip/stored_normal.h"

namespace svbrdf {
namespace {

// Unit directions over the whole sphere and, every other one, within 10° of the pole (where a coarse
// level's normals gather), at lengths from 1 down to 0.3 (normals that spread) and just below 1.
glm::vec3 sample_normal(std::mt19937& rng, int k) {
  std::normal_distribution<double> g;
  glm::dvec3 d = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
  if (k % 2) d = glm::normalize(glm::dvec3(0.1 * d.x, 0.1 * d.y, std::abs(d.z)));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double lengths[4] = {1.0, 1.0 - 1e-7 * u(rng), 1.0 - 1e-3 * u(rng), 0.3 + 0.7 * u(rng)};
  return glm::vec3(d * lengths[k % 4]);
}

// The angle between a normal and its stored form.
double rounding_angle(const glm::vec3& n) {
  const glm::vec3 r = round_normal(n);
  const double len = glm::length(glm::dvec3(n)), back = glm::length(glm::dvec3(r));
  return std::acos(std::min(1.0, glm::dot(glm::dvec3(r) / back, glm::dvec3(n) / len)));
}

TEST(StoredNormal, DirectionWithinHalfACellDiagonalAndLengthOnItsGrid) {
  // A code cell is 1/32767 on a side in the code's coordinates c. The octahedral coordinate is
  // p = c·(1/16 + (15/16)|c|), whose slope is at most 2 − 1/16 (at |c| = 1), and the octahedral map
  // stretches directions by at most 2 (along the diagonal at the middle of the octahedron's edges), so a
  // cell's half-diagonal is at most (2 − 1/16)·√2/32767 = 8.36e-5 rad. The nearest of the four codes
  // around a direction stays within it; the linear code's bound was √2/32767.
  const double max_angle = (2.0 - 1.0 / 16) * std::sqrt(2.0) / 32767;
  std::mt19937 rng(7);
  double worst = 0;
  for (int k = 0; k < 200000; ++k) {
    const glm::vec3 n = sample_normal(rng, k);
    const glm::vec3 r = round_normal(n);
    const double len = glm::length(glm::dvec3(n)), back = glm::length(glm::dvec3(r));
    const double angle = rounding_angle(n);
    worst = std::max(worst, angle);
    ASSERT_LE(angle, max_angle) << n.x << " " << n.y << " " << n.z;
    // The deficit 1 − len: a multiple of 2^-20 (half a step off), then a half float (2^-11 relative).
    ASSERT_NEAR(back, len, 0x1p-21 + 0x1p-11 * (1 - len) + 2e-7) << n.x << " " << n.y << " " << n.z;
  }
  EXPECT_GT(worst, 0.4 * max_angle) << "the bound is far from what the codes reach: is the grid finer than documented?";
}

// Near the pole, where a coarse level's normals gather, the warp's cells are small. Within a tilt t of
// the pole the octahedral coordinates are at most p = tan t, where the slope of p(c) is at most
// 1/16 + (15/8)·c(p), c(p) = (−1/16 + √(1/256 + (15/4)p))/(15/8) the code coordinate of p; the map's
// stretch there is 1 + O(p) (3 % allowed). So a normal within 1° is stored within 0.263·√2/32767 =
// 1.14e-5 rad, and one within 0.01° within 0.068·√2/32767 = 2.9e-6 rad, where the linear code's cells
// were 4.3e-5 rad wide everywhere. The polished tray's re-centring moves lobes by ~1.5e-5 rad
// (radial_correction.h).
TEST(StoredNormal, FineNearThePole) {
  constexpr double kPi = 3.14159265358979323846, a = 1.0 / 16;
  const auto bound = [&](double tilt_deg) {
    const double p = std::tan(tilt_deg * kPi / 180), c = (-a + std::sqrt(a * a + 4 * (1 - a) * p)) / (2 * (1 - a));
    return 1.03 * (a + 2 * (1 - a) * c) * std::sqrt(2.0) / 32767;
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const double max_tilt : {1.0, 0.01}) {
    const double max_angle = bound(max_tilt);
    double worst = 0;
    for (int k = 0; k < 100000; ++k) {
      const double phi = 2 * kPi * u(rng), tilt = max_tilt * u(rng) * kPi / 180;
      const glm::vec3 n(std::sin(tilt) * std::cos(phi), std::sin(tilt) * std::sin(phi), std::cos(tilt));
      const double angle = rounding_angle(n);
      ASSERT_LE(angle, max_angle) << "tilt " << tilt << " rad";
      worst = std::max(worst, angle);
    }
    EXPECT_GT(worst, 0.3 * max_angle) << "within " << max_tilt << "°: the bound is far from what the codes reach";
  }
}

TEST(StoredNormal, EncodingADecodedNormalGivesItsCodeBack) {
  std::mt19937 rng(11);
  // Codes of normals, and codes at the folded square's edges and corners, where two codes can name
  // one direction.
  for (int k = 0; k < 200000; ++k) {
    const StoredNormal s = store_normal(sample_normal(rng, k));
    const StoredNormal again = store_normal(load_normal(s));
    ASSERT_EQ(again.direction, s.direction) << k;
    ASSERT_EQ(again.deficit, s.deficit) << k;
  }
  // Normals of the lower hemisphere just off the planes x = 0 and y = 0: the folded square's edges,
  // where the four candidate codes straddle the fold.
  std::normal_distribution<double> g;
  for (int k = 0; k < 200000; ++k) {
    const double tiny = 1e-5 * g(rng), a = g(rng), b = -std::abs(g(rng));
    const glm::dvec3 d = k % 2 ? glm::dvec3(tiny, a, b) : glm::dvec3(a, tiny, b);
    const StoredNormal s = store_normal(glm::vec3(glm::normalize(d)));
    const StoredNormal again = store_normal(load_normal(s));
    ASSERT_EQ(again.direction, s.direction) << d.x << " " << d.y << " " << d.z;
  }
  std::uniform_int_distribution<int> q(-32767, 32767);
  for (int k = 0; k < 20000; ++k) {
    const int a = q(rng), edge = (k % 2 ? 32767 : -32767);
    for (auto [x, y] : {std::pair{a, edge}, std::pair{edge, a}, std::pair{edge, k % 4 < 2 ? 32767 : -32767}}) {
      const std::uint32_t code = static_cast<std::uint16_t>(static_cast<std::int16_t>(x)) |
                                 static_cast<std::uint32_t>(static_cast<std::uint16_t>(static_cast<std::int16_t>(y))) << 16;
      const StoredNormal once = store_normal(load_normal(StoredNormal{code, 0.0f}));
      const StoredNormal twice = store_normal(load_normal(once));
      ASSERT_EQ(twice.direction, once.direction) << x << " " << y;
      // And the direction is the one coded: one code per direction, not a different direction.
      ASSERT_GT(glm::dot(load_normal(once), load_normal(StoredNormal{code, 0.0f})), 1.0f - 1e-6f) << x << " " << y;
    }
  }
  // Every deficit a half float holds in [0, 1] that lies on the 2^-20 grid, about a tilted direction.
  for (std::uint32_t bits = 0; bits <= 0x3c00u; ++bits) {
    const float deficit = glm::unpackHalf1x16(static_cast<std::uint16_t>(bits));
    if (std::fmod(double(deficit), 0x1p-20) != 0.0) continue;
    const StoredNormal s = store_normal(glm::normalize(glm::vec3(0.3f, -0.2f, 0.9f)) * (1.0f - deficit));
    ASSERT_EQ(s.deficit, deficit) << bits;
    const StoredNormal again = store_normal(load_normal(s));
    ASSERT_EQ(again.deficit, s.deficit) << bits;
    ASSERT_EQ(again.direction, s.direction) << bits;
  }
}

TEST(StoredNormal, AxesAndZeroLengthAreExact) {
  for (const glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0, -1, 0)})
    EXPECT_EQ(round_normal(n), n);
  EXPECT_EQ(round_normal(glm::vec3(0, 0, 0.5f)), glm::vec3(0, 0, 0.5f));
  EXPECT_EQ(round_normal(glm::vec3(0)), glm::vec3(0));
}

}  // namespace
}  // namespace svbrdf
