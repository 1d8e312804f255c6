#pragma once
// Float images in memory: linear values, interleaved channels, rows from the top (as stored in
// files and as glTF's uv (0,0) = top-left means them). Every file read and write goes through
// OpenImageIO.
#include <cstddef>
#include <filesystem>
#include <vector>

namespace svbrdf {

struct Image {
  int width = 0;
  int height = 0;
  int channels = 0;
  std::vector<float> pixels;  // width * height * channels, row-major from the top row

  Image() = default;
  Image(int w, int h, int c) : width(w), height(h), channels(c), pixels(std::size_t(w) * h * c, 0.0f) {}

  float& at(int x, int y, int c) { return pixels[(std::size_t(y) * width + x) * channels + c]; }
  float at(int x, int y, int c) const { return pixels[(std::size_t(y) * width + x) * channels + c]; }
};

// Reads any format OpenImageIO reads into floats (values as stored: no color conversion).
// Throws svbrdf::Error naming the file when it is missing, truncated or corrupt.
Image read_image(const std::filesystem::path& path);

enum class PixelFormat { uint8, uint16, half, float32 };

// Writes through OpenImageIO, choosing the format by extension, atomically (temporary + rename).
void write_image(const std::filesystem::path& path, const Image& image, PixelFormat format);

}  // namespace svbrdf
