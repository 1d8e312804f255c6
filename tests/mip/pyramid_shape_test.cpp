#include "mip/pyramid_shape.h"

#include <gtest/gtest.h>

namespace svbrdf {
namespace {

// Each level halves (rounding down, never below 1) until 1×1; the count follows from the longest side.
TEST(PyramidShape, LevelsHalveDownToOne) {
  EXPECT_EQ(level_count({1, 1}), 1);
  EXPECT_EQ(level_count({1024, 1024}), 11);
  EXPECT_EQ(level_count({1024, 256}), 11);
  EXPECT_EQ(level_count({5, 3}), 3);
  EXPECT_EQ(level_extent({1024, 256}, 0), (Extent{1024, 256}));
  EXPECT_EQ(level_extent({1024, 256}, 9), (Extent{2, 1}));
  EXPECT_EQ(level_extent({1024, 256}, 10), (Extent{1, 1}));
  // The last level of every pyramid is 1×1.
  for (int w : {1, 2, 3, 7, 64, 100, 4096})
    for (int h : {1, 5, 64, 333}) EXPECT_EQ(level_extent({w, h}, level_count({w, h}) - 1), (Extent{1, 1}));
  EXPECT_TRUE(is_power_of_two(512));
  EXPECT_FALSE(is_power_of_two(0));
  EXPECT_FALSE(is_power_of_two(384));
}

}  // namespace
}  // namespace svbrdf
