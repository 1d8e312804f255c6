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

TEST(StoredNormal, DirectionWithinHalfACellDiagonalAndLengthOnItsGrid) {
  // A code cell is 1/32767 on a side in the octahedron's coordinates; the map stretches directions by
  // 2 along the diagonal at the middle of the octahedron's edges, which makes a cell's half-diagonal
  // √2/32767 = 4.32e-5 rad there. The nearest of the four codes around a direction stays within it
  // (4.29e-5 at most over 2e6 directions); the nearest in the coordinates alone does not (6.4e-5).
  const double max_angle = std::sqrt(2.0) / 32767;
  std::mt19937 rng(7);
  double worst = 0;
  for (int k = 0; k < 200000; ++k) {
    const glm::vec3 n = sample_normal(rng, k);
    const glm::vec3 r = round_normal(n);
    const double len = glm::length(glm::dvec3(n)), back = glm::length(glm::dvec3(r));
    const double angle = std::acos(std::min(1.0, glm::dot(glm::dvec3(r) / back, glm::dvec3(n) / len)));
    worst = std::max(worst, angle);
    ASSERT_LE(angle, max_angle) << n.x << " " << n.y << " " << n.z;
    // The deficit 1 − len: a multiple of 2^-20 (half a step off), then a half float (2^-11 relative).
    ASSERT_NEAR(back, len, 0x1p-21 + 0x1p-11 * (1 - len) + 2e-7) << n.x << " " << n.y << " " << n.z;
  }
  EXPECT_GT(worst, 0.5 * max_angle) << "the bound is far from what the codes reach: is the grid finer than documented?";
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
