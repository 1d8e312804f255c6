// base/series_log.h against libm (the independent reference), over the ranges its callers use and
// at the edges its comments promise.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "base/series_log.h"

namespace svbrdf {
namespace {

TEST(Series, LogWithinOneInABillion) {
  for (double x = 1e-12; x < 1e12; x *= 1.0137) EXPECT_NEAR(series_log(x), std::log(x), 1e-9) << x;
}

TEST(Series, Log2WithinThreeInAHundredThousandAndExactAtPowersOfTwo) {
  for (float x = 1e-30f; x < 1e30f; x *= 1.0173f) EXPECT_NEAR(series_log2(x), std::log2(x), 3e-5) << x;
  for (int k = -126; k < 128; ++k) EXPECT_EQ(series_log2(std::ldexp(1.0f, k)), static_cast<float>(k));
}

// The float logarithm the lobes' shapes take of their α² ratio: relative to ln x near 1 (a narrow
// mixture's span, whose ratio x − 1 the shape divides by it), absolute elsewhere.
TEST(Series, LogfRelativeNearOneAndWithinAFloatElsewhere) {
  for (float x = 1.0f + 1.2e-7f; x <= 2.0f; x *= 1.0011f) {
    const double want = std::log(static_cast<double>(x));
    EXPECT_NEAR(series_logf(x) / want, 1.0, 5e-7) << x;
  }
  for (float x = 1e-30f; x < 1e30f; x *= 1.0173f) {
    const double want = std::log(static_cast<double>(x));
    EXPECT_NEAR(series_logf(x), want, 2.5e-7 * std::max(1.0, std::abs(want))) << x;
  }
}

TEST(Series, ExpWithinFourInTenMillion) {
  for (float x = -87.0f; x <= 88.0f; x += 0.00731f) {
    const double want = std::exp(static_cast<double>(x));
    EXPECT_NEAR(series_exp(x) / want, 1.0, 4e-7) << x;
  }
  EXPECT_EQ(series_exp(0.0f), 1.0f);
  EXPECT_EQ(series_exp(-100.0f), 0.0f);
  EXPECT_EQ(series_exp(-INFINITY), 0.0f);
  EXPECT_TRUE(std::isfinite(series_exp(1000.0f)));
}

}  // namespace
}  // namespace svbrdf
