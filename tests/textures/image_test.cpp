#include "textures/image.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "base/error.h"

namespace svbrdf {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() {
  fs::path d = fs::temp_directory_path() / ("svbrdf_image_test_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

Image gradient(int w, int h, int c) {
  Image img(w, h, c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) img.at(x, y, k) = float(x + 3 * y + 7 * k) / float(w + 3 * h + 7 * c);
  return img;
}

// An OpenEXR float image comes back bit-identical; a 16-bit PNG to within its quantization.
TEST(Image, RoundTripThroughOpenImageIO) {
  const fs::path dir = temp_dir();
  const Image src = gradient(17, 9, 3);

  write_image(dir / "g.exr", src, PixelFormat::float32);
  const Image exr = read_image(dir / "g.exr");
  ASSERT_EQ(exr.width, 17);
  ASSERT_EQ(exr.height, 9);
  ASSERT_EQ(exr.channels, 3);
  EXPECT_EQ(exr.pixels, src.pixels);

  write_image(dir / "g.png", src, PixelFormat::uint16);
  const Image png = read_image(dir / "g.png");
  ASSERT_EQ(png.pixels.size(), src.pixels.size());
  for (std::size_t i = 0; i < src.pixels.size(); ++i) EXPECT_NEAR(png.pixels[i], src.pixels[i], 0.5 / 65535 + 1e-7);
  fs::remove_all(dir);
}

TEST(Image, MissingFileIsAnErrorNamingIt) {
  try {
    read_image("/nonexistent/dir/missing.png");
    FAIL() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos) << e.what();
    EXPECT_EQ(e.exit_code(), 2);
  }
}

}  // namespace
}  // namespace svbrdf
