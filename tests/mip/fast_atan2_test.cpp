// base/fast_atan2.h against libm's atan2 (the independent reference), around the whole circle and at
// the edges (axes, zeros, huge and tiny ratios).
#include <gtest/gtest.h>

#include <cmath>

#include "base/fast_atan2.h"

namespace svbrdf {
namespace {

TEST(FastAtan2, WithinSixInTenMillionRadiansAroundTheCircle) {
  for (double t = -3.14159; t < 3.14159; t += 1.3e-4)
    for (float r : {1e-20f, 1e-3f, 1.0f, 7.5f, 1e20f}) {
      const float x = r * static_cast<float>(std::cos(t)), y = r * static_cast<float>(std::sin(t));
      EXPECT_NEAR(fast_atan2(y, x), std::atan2(y, x), 6e-7) << y << " " << x;
    }
}

TEST(FastAtan2, AxesZerosAndExtremeRatios) {
  const float pi = 3.14159265358979323846f;
  EXPECT_EQ(fast_atan2(0.0f, 1.0f), 0.0f);
  EXPECT_EQ(fast_atan2(0.0f, 0.0f), 0.0f);
  EXPECT_NEAR(fast_atan2(1.0f, 0.0f), pi / 2, 1e-7);
  EXPECT_NEAR(fast_atan2(-1.0f, 0.0f), -pi / 2, 1e-7);
  EXPECT_NEAR(fast_atan2(0.0f, -1.0f), pi, 1e-7);
  EXPECT_NEAR(fast_atan2(-0.0f, -1.0f), -pi, 1e-7);
  EXPECT_NEAR(fast_atan2(1e-30f, 1e30f), 0.0f, 1e-30);
  EXPECT_NEAR(fast_atan2(1e30f, -1e-30f), pi / 2, 1e-7);
  EXPECT_TRUE(std::isnan(fast_atan2(NAN, 1.0f)));
  EXPECT_TRUE(std::isnan(fast_atan2(1.0f, NAN)));
}

}  // namespace
}  // namespace svbrdf
