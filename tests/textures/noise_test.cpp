#include "textures/noise.h"

#include <gtest/gtest.h>

#include <cmath>

namespace svbrdf {
namespace {

// The families tile because their noise is periodic over the texture: shifting by a whole period
// gives the same value (up to the rounding of the shifted coordinate).
TEST(Noise, PeriodicOverTheTexture) {
  noise::Sequence rng(11, 0);
  for (int k = 0; k < 200; ++k) {
    const double u = rng.uniform(), v = rng.uniform();
    const int p = 1 + int(rng.uniform() * 40.0f);
    EXPECT_NEAR(noise::gradient(3, u * p, v * p, p, p), noise::gradient(3, u * p + p, v * p - p, p, p), 1e-5);
    EXPECT_NEAR(noise::gradient1(3, u * p, p), noise::gradient1(3, u * p + 2 * p, p), 1e-5);
    EXPECT_NEAR(noise::fbm(5, u, v, p, 3), noise::fbm(5, u + 1.0, v - 1.0, p, 3), 1e-5);
    const noise::CellularHit a = noise::cellular(7, u, v, p), b = noise::cellular(7, u - 1.0, v + 2.0, p);
    EXPECT_NEAR(a.f1, b.f1, 1e-4);
    EXPECT_EQ(a.cell_x, b.cell_x);
    EXPECT_EQ(a.cell_y, b.cell_y);
  }
}

// Gradient noise is zero on the lattice and stays within its theoretical bound (√2/2 for unit
// gradients); cellular F1 ≤ F2, and F1 is the distance to the reported feature.
TEST(Noise, RangesAndLatticeZeros) {
  noise::Sequence rng(12, 0);
  for (int k = 0; k < 2000; ++k) {
    const double x = rng.uniform(0.0f, 50.0f), y = rng.uniform(0.0f, 50.0f);
    EXPECT_LE(std::abs(noise::gradient(9, x, y, 64, 64)), 0.7072f);
    EXPECT_NEAR(noise::gradient(9, std::floor(x), std::floor(y), 64, 64), 0.0f, 1e-6);
    const noise::CellularHit h = noise::cellular(9, x / 50.0, y / 50.0, 20);
    EXPECT_LE(h.f1, h.f2);
    EXPECT_NEAR(glm::length(h.to_nearest), h.f1, 1e-5);
    EXPECT_LT(h.f1, 1.5f);  // a feature lies in every cell
  }
  // Uniform numbers: in [0, 1), mean 1/2 within 4σ for 10^5 draws.
  double sum = 0;
  for (int k = 0; k < 100000; ++k) {
    const float x = noise::unit(42, k);
    ASSERT_TRUE(x >= 0.0f && x < 1.0f);
    sum += x;
  }
  EXPECT_NEAR(sum / 1e5, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / 1e5));
  EXPECT_EQ(noise::cells_for(100.0, 2.0), 50);
  EXPECT_EQ(noise::cells_for(1.0, 2.0), 1);
}

}  // namespace
}  // namespace svbrdf
