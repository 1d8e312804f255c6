#pragma once
// Test helper: a MipTexture's records (mip/mip_records.h) held in memory, one vector a level, as a
// MipRecordSource; each record read is checked to lie inside its level.
#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "mip/mip.h"
#include "mip/mip_records.h"

namespace svbrdf::testing_records {

class Records final : public MipRecordSource {
 public:
  Records(const MipTexture& t, const MipRecordLayout& layout) : layout_(layout) {
    for (int l = 0; l < layout.levels; ++l) {
      const Extent e = level_extent(layout.extent, l);
      levels_.emplace_back(std::size_t(e.width) * std::size_t(e.height) * std::size_t(layout.words(l)));
      t.encode_records(layout, l, 0, e.height, levels_.back().data());
    }
  }
  const std::uint32_t* record(int level, int i, int j) const override {
    const Extent e = level_extent(layout_.extent, level);
    EXPECT_TRUE(i >= 0 && i < e.width && j >= 0 && j < e.height) << level << " " << i << " " << j;
    return levels_[std::size_t(level)].data() +
           (std::size_t(j) * std::size_t(e.width) + std::size_t(i)) * std::size_t(layout_.words(level));
  }
  std::vector<std::vector<std::uint32_t>> levels_;

 private:
  MipRecordLayout layout_;
};

}  // namespace svbrdf::testing_records
