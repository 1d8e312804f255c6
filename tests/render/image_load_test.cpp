// The scene reader holds one image at a time (gltf/document.h: an image file beside the glTF is read
// only when its image is decoded, and its bytes dropped after), so a load's peak does not grow with
// the number of images the scene has.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/common/temp_dir.h"
#include "tests/render/quad_row.h"
#include "tests/render/render_child.h"
#include "textures/image.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

// A hash of (seed, i, j, c) to [0, 1): texels that do not compress, so that a PNG is about as large as
// its texels (the encoded bytes are what the loader must not hold all at once).
float noise(std::uint32_t seed, int i, int j, int c) {
  std::uint32_t h = seed * 0x9E3779B9u ^ std::uint32_t(i) * 0x85EBCA6Bu ^ std::uint32_t(j) * 0xC2B2AE35u ^
                    std::uint32_t(c) * 0x27D4EB2Fu;
  h ^= h >> 15, h *= 0x2C1B3C6Du, h ^= h >> 12, h *= 0x297A2D39u, h ^= h >> 15;
  return float(h >> 8) / float(1u << 24);
}

// A load holds one image at a time: its encoded bytes, read just before it is decoded, its floats,
// their linearized copy and its codes (4 + 16 + 16 + 4 bytes a texel: 10.5 MB at 512²). The bound on
// what a cold load through the texture cache and a frame of 16 × 8 pixels hold beyond the same scene
// untextured: one and a half such images, the one in flight and half again for the allocator's slack.
// The 24 PNGs' bytes alone are 24 × 1 MB of 512² RGBA noise, more than the bound: a load that held
// them all at once fails it (measured 4 MB above; 40 MB when the bytes were all held, on the code before the MIP data went out of core). The bound
// is of what one image costs, whatever the number of images.
TEST(ImageLoad, TheLoadHoldsAFewImagesAtATimeWhateverTheirNumber) {
  const testing::TempDir dir;
  constexpr int kCount = 24, kSide = 512;
  const fs::path textured = testing::quads(dir.path(), kCount, kSide, true);
  const fs::path plain = testing::quads(dir.path(), kCount, kSide, false);
  // The quads' smooth textures replaced by noise of the same size.
  for (int k = 0; k < kCount; ++k) {
    Image im(kSide, kSide, 4);
    for (int j = 0; j < kSide; ++j)
      for (int i = 0; i < kSide; ++i)
        for (int c = 0; c < 4; ++c) im.at(i, j, c) = noise(std::uint32_t(k + 1), i, j, c);
    std::string name = "t";
    name += std::to_string(k);
    name += ".png";
    write_image(dir.path() / name, im, PixelFormat::uint8);
  }
  const std::vector<std::string> common = {"--res", "16x8", "--spp", "1", "--filter", "level0", "--threads", "2", "-q",
                                           "--mip-cache", (dir.path() / "cache").string(), "-o",
                                           (dir.path() / "x.exr").string()};
  auto with = [&](const fs::path& scene, std::vector<std::string> extra) {
    std::vector<std::string> a = {scene.string()};
    a.insert(a.end(), common.begin(), common.end());
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  };
  const testing::Child base = testing::render_child(with(plain, {}), dir.path());
  ASSERT_EQ(base.status, 0) << base.err;
  const testing::Child cold = testing::render_child(with(textured, {"--texture-cache", "10"}), dir.path());
  ASSERT_EQ(cold.status, 0) << cold.err;
  const double image_mb = 40.0 * kSide * kSide / 1e6, bound_mb = 1.5 * image_mb;
  const double above_mb = double(cold.peak_kb - base.peak_kb) * 1024 / 1e6;
  std::printf("cold load of %d images of %d²: %.1f MB above the untextured scene (bound %.1f MB)\n", kCount, kSide,
              above_mb, bound_mb);
  EXPECT_LT(above_mb, bound_mb) << "peak " << cold.peak_kb << " kB against " << base.peak_kb << " kB untextured";
}

}  // namespace
}  // namespace svbrdf
