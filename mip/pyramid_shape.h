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

// A half-open range of texel indices along one axis.
struct Span {
  int begin = 0;
  int end = 0;
  int size() const { return end - begin; }
};

// The level-0 columns (or rows) that texel `index` of `level` covers along an axis whose level-0 size
// is `size0`: [index·2^L, (index+1)·2^L), as the spec says for power-of-two sizes. For other sizes the
// last texel of a level also covers the remainder [index·2^L, size0), so that every level-0 texel
// belongs to exactly one texel of every level, and a level where the axis has shrunk to 1 covers it
// all. Coarse texels then cover unequal counts; means are weighted by those counts.
inline Span level0_span(int size0, int level, int index) {
  const int extent = std::max(1, size0 >> level);
  const int begin = index << level;
  return {begin, index == extent - 1 ? size0 : (index + 1) << level};
}

// The texels of level − 1 that texel `index` of `level` (≥ 1) is made of, consistent with
// level0_span: two, or three where the finer level has an odd extent, or one where both are 1.
inline Span child_span(int size0, int level, int index) {
  const int fine = std::max(1, size0 >> (level - 1));
  const int extent = std::max(1, size0 >> level);
  return {2 * index, index == extent - 1 ? fine : 2 * index + 2};
}

}  // namespace svbrdf
