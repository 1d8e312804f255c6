// Compares two display PNGs of the same scene (Cycles' and svbrdf-render's) in 8-bit values: the mean
// absolute difference over every pixel and RGB channel must not exceed a bound. Prints what a failure
// needs to be understood: each image's mean per channel, the share of pixels off by more than 32/255,
// the mean signed difference over a 4×3 grid of tiles, and the worst pixel.
//
//   compare-png A.png B.png --max-mad 8 [--diff DIFF.png]
//
// Exit 0 within the bound, 1 beyond it, 2 for unreadable or mismatched images.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

struct Rgb8 {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // rows from the top, 3 values a pixel
  int at(int x, int y, int c) const { return rgb[(std::size_t(y) * width + x) * 3 + c]; }
};

bool read_rgb8(const std::string& path, Rgb8& out) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) {
    std::fprintf(stderr, "compare-png: cannot read %s: %s\n", path.c_str(), OIIO::geterror().c_str());
    return false;
  }
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.nchannels < 3) {
    std::fprintf(stderr, "compare-png: %s has %d channels, not RGB\n", path.c_str(), spec.nchannels);
    return false;
  }
  out.width = spec.width;
  out.height = spec.height;
  out.rgb.resize(std::size_t(spec.width) * spec.height * 3);
  if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, out.rgb.data())) {
    std::fprintf(stderr, "compare-png: cannot decode %s: %s\n", path.c_str(), in->geterror().c_str());
    return false;
  }
  return true;
}

std::array<double, 3> channel_means(const Rgb8& img) {
  std::array<double, 3> sum{};
  for (std::size_t i = 0; i < img.rgb.size(); ++i) sum[i % 3] += img.rgb[i];
  const double n = double(img.width) * img.height;
  return {sum[0] / n, sum[1] / n, sum[2] / n};
}

int usage() {
  std::fprintf(stderr, "usage: compare-png A.png B.png --max-mad N [--diff DIFF.png]  (N in 1/255)\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> files;
  std::string diff_path;
  double max_mad = -1.0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--max-mad" && i + 1 < argc) max_mad = std::atof(argv[++i]);
    else if (arg == "--diff" && i + 1 < argc) diff_path = argv[++i];
    else if (arg.rfind("--", 0) == 0) return usage();
    else files.push_back(arg);
  }
  if (files.size() != 2 || max_mad < 0.0) return usage();
  Rgb8 a, b;
  if (!read_rgb8(files[0], a) || !read_rgb8(files[1], b)) return 2;
  if (a.width != b.width || a.height != b.height) {
    std::fprintf(stderr, "compare-png: %s is %dx%d, %s is %dx%d\n", files[0].c_str(), a.width, a.height,
                 files[1].c_str(), b.width, b.height);
    return 2;
  }

  constexpr int kTilesX = 4, kTilesY = 3, kFar = 32;
  double abs_sum = 0.0;
  std::size_t far_pixels = 0;
  std::array<double, kTilesX * kTilesY> tile_sum{}, tile_count{};
  int worst = -1, worst_x = 0, worst_y = 0;
  std::vector<unsigned char> diff(a.rgb.size());
  for (int y = 0; y < a.height; ++y) {
    for (int x = 0; x < a.width; ++x) {
      int pixel_max = 0;
      const int tile = (y * kTilesY / a.height) * kTilesX + x * kTilesX / a.width;
      for (int c = 0; c < 3; ++c) {
        const int d = b.at(x, y, c) - a.at(x, y, c);
        abs_sum += std::abs(d);
        tile_sum[tile] += d;
        pixel_max = std::max(pixel_max, std::abs(d));
        diff[(std::size_t(y) * a.width + x) * 3 + c] = static_cast<unsigned char>(std::min(255, 4 * std::abs(d)));
      }
      tile_count[tile] += 3;
      if (pixel_max > kFar) ++far_pixels;
      if (pixel_max > worst) worst = pixel_max, worst_x = x, worst_y = y;
    }
  }
  const double pixels = double(a.width) * a.height, mad = abs_sum / (3.0 * pixels);
  const auto ma = channel_means(a), mb = channel_means(b);

  std::printf("A: %s\nB: %s (%dx%d)\n", files[0].c_str(), files[1].c_str(), a.width, a.height);
  std::printf("mean R G B of A: %6.2f %6.2f %6.2f /255\n", ma[0], ma[1], ma[2]);
  std::printf("mean R G B of B: %6.2f %6.2f %6.2f /255\n", mb[0], mb[1], mb[2]);
  std::printf("pixels with a channel off by more than %d/255: %.2f%%\n", kFar, 100.0 * far_pixels / pixels);
  std::printf("mean B - A by tile (%dx%d, rows from the top), /255:\n", kTilesX, kTilesY);
  for (int ty = 0; ty < kTilesY; ++ty) {
    std::printf("  ");
    for (int tx = 0; tx < kTilesX; ++tx)
      std::printf(" %+7.2f", tile_sum[ty * kTilesX + tx] / std::max(1.0, tile_count[ty * kTilesX + tx]));
    std::printf("\n");
  }
  std::printf("largest difference %d/255 at pixel (%d, %d): A %d %d %d, B %d %d %d\n", worst, worst_x, worst_y,
              a.at(worst_x, worst_y, 0), a.at(worst_x, worst_y, 1), a.at(worst_x, worst_y, 2),
              b.at(worst_x, worst_y, 0), b.at(worst_x, worst_y, 1), b.at(worst_x, worst_y, 2));
  const bool pass = mad <= max_mad;
  std::printf("MAD %.2f/255 (bound %.2f/255): %s\n", mad, max_mad, pass ? "pass" : "FAIL");

  if (!diff_path.empty()) {
    OIIO::ImageBuf buf(OIIO::ImageSpec(a.width, a.height, 3, OIIO::TypeDesc::UINT8), diff.data());
    if (!buf.write(diff_path)) std::fprintf(stderr, "compare-png: cannot write %s\n", diff_path.c_str());
  }
  return pass ? 0 : 1;
}
