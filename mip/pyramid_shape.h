#pragma once
// The shape of a MIP pyramid: level L of a w×h level-0 image is max(1, w>>L) × max(1, h>>L), down
// to 1×1 (../shared/spec/brdf-mip.md: level-L texel (i, j) covers level-0 columns [i·2^L, (i+1)·2^L)
// and rows [j·2^L, (j+1)·2^L)).
#include <algorithm>
#include <bit>
#include <cstdint>

namespace svbrdf {

struct Extent {
  int width = 0;
  int height = 0;
  bool operator==(const Extent&) const = default;
};

inline int level_count(Extent level0) {
  const auto longest = static_cast<std::uint32_t>(std::max(level0.width, level0.height));
  return longest == 0 ? 0 : std::bit_width(longest);
}

inline Extent level_extent(Extent level0, int level) {
  return {std::max(1, level0.width >> level), std::max(1, level0.height >> level)};
}

inline bool is_power_of_two(int n) { return n > 0 && std::has_single_bit(static_cast<std::uint32_t>(n)); }

}  // namespace svbrdf
