#include "lod/metrics.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace svbrdf {

std::vector<std::uint8_t> object_mask(const Image& depth) {
  std::vector<std::uint8_t> mask(std::size_t(depth.width) * depth.height, 0);
  for (int y = 0; y < depth.height; ++y)
    for (int x = 0; x < depth.width; ++x) mask[std::size_t(y) * depth.width + x] = depth.at(x, y, 0) > 0.0f;
  return mask;
}

double luminance(const Image& im, int x, int y) {
  return 0.2126 * im.at(x, y, 0) + 0.7152 * im.at(x, y, 1) + 0.0722 * im.at(x, y, 2);
}

LodMetrics compare_images(const Image& X, const Image& R, const std::vector<std::uint8_t>& mask) {
  if (X.width != R.width || X.height != R.height || X.channels < 3 || R.channels < 3 ||
      mask.size() != std::size_t(R.width) * R.height)
    throw Error("LOD metrics: images of different sizes", Error::Kind::internal);
  double se = 0, ref2 = 0, sum_x = 0, sum_r = 0, peak_x = 0, peak_r = 0;
  std::size_t n = 0;
  for (int y = 0; y < R.height; ++y)
    for (int x = 0; x < R.width; ++x) {
      if (!mask[std::size_t(y) * R.width + x]) continue;
      ++n;
      for (int c = 0; c < 3; ++c) {
        const double a = X.at(x, y, c), b = R.at(x, y, c);
        se += (a - b) * (a - b);
        ref2 += b * b;
        sum_x += a;
        sum_r += b;
      }
      peak_x = std::max(peak_x, luminance(X, x, y));
      peak_r = std::max(peak_r, luminance(R, x, y));
    }
  if (n == 0 || ref2 <= 0 || peak_r <= 0)
    throw Error("LOD metrics: the object mask is empty or the reference is black over it", Error::Kind::internal);
  return {se / ref2, sum_x / sum_r - 1.0, peak_x / peak_r};
}

double flux_noise(const Image& a, const Image& b, const std::vector<std::uint8_t>& mask) {
  if (a.width != b.width || a.height != b.height || mask.size() != std::size_t(a.width) * a.height)
    throw Error("LOD metrics: images of different sizes", Error::Kind::internal);
  double var = 0, sum = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (!mask[std::size_t(y) * a.width + x]) continue;
      double sa = 0, sb = 0;
      for (int c = 0; c < 3; ++c) sa += a.at(x, y, c), sb += b.at(x, y, c);
      var += 0.5 * (sa - sb) * (sa - sb);
      sum += sa;
    }
  if (sum <= 0) throw Error("LOD metrics: the reference is black over the mask", Error::Kind::internal);
  return std::sqrt(var) / sum;
}

void error_color(double t, float rgb[3]) {
  // Control points sampled from matplotlib's "inferno" (perceptually uniform, black at 0).
  static const float stops[][3] = {{0.001f, 0.000f, 0.014f}, {0.258f, 0.039f, 0.406f}, {0.578f, 0.148f, 0.404f},
                                   {0.865f, 0.317f, 0.226f}, {0.988f, 0.645f, 0.040f}, {0.988f, 0.998f, 0.645f}};
  constexpr int n = 6;
  t = std::clamp(t, 0.0, 1.0) * (n - 1);
  const int i = std::min(int(t), n - 2);
  const float f = float(t - i);
  for (int c = 0; c < 3; ++c) rgb[c] = stops[i][c] + f * (stops[i + 1][c] - stops[i][c]);
}

Image false_color_error(const Image& X, const Image& R, const std::vector<std::uint8_t>& mask, double full_scale) {
  double mean = 0;
  std::size_t n = 0;
  for (int y = 0; y < R.height; ++y)
    for (int x = 0; x < R.width; ++x)
      if (mask[std::size_t(y) * R.width + x]) mean += luminance(R, x, y), ++n;
  mean = n ? mean / double(n) : 1.0;
  if (mean <= 0) mean = 1.0;
  Image out(R.width, R.height, 3);
  for (int y = 0; y < R.height; ++y)
    for (int x = 0; x < R.width; ++x) {
      float rgb[3] = {0.5f, 0.5f, 0.5f};
      if (mask[std::size_t(y) * R.width + x])
        error_color(std::abs(luminance(X, x, y) - luminance(R, x, y)) / mean / full_scale, rgb);
      for (int c = 0; c < 3; ++c) out.at(x, y, c) = rgb[c];
    }
  return out;
}

}  // namespace svbrdf
