#include "textures/noise.h"
#include "base/math.h"

#include <array>
#include <cmath>
#include <limits>

namespace svbrdf::noise {

namespace {

int wrap(long long i, int period) {
  const long long r = i % period;
  return static_cast<int>(r < 0 ? r + period : r);
}

// Perlin's quintic fade 6t^5 − 15t^4 + 10t^3: C2 across lattice lines.
float fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }

// Gradients are drawn from 256 unit vectors at evenly spaced angles (Perlin 2002 also picks from a
// fixed set): a table lookup instead of a sine and cosine per lattice corner.
const std::array<glm::vec2, 256>& gradient_table() {
  static const std::array<glm::vec2, 256> table = [] {
    std::array<glm::vec2, 256> t{};
    for (int k = 0; k < 256; ++k) {
      const double a = 2.0 * kPiD * (k + 0.5) / 256.0;
      t[k] = glm::vec2(float(std::cos(a)), float(std::sin(a)));
    }
    return t;
  }();
  return table;
}

glm::vec2 lattice_gradient(std::uint64_t seed, int ix, int iy) { return gradient_table()[hash(seed, ix, iy, 0x67) >> 56]; }

}  // namespace

float gradient(std::uint64_t seed, double x, double y, int period_x, int period_y) {
  const double fx = std::floor(x), fy = std::floor(y);
  const float tx = static_cast<float>(x - fx), ty = static_cast<float>(y - fy);
  const int x0 = wrap(static_cast<long long>(fx), period_x), x1 = wrap(static_cast<long long>(fx) + 1, period_x);
  const int y0 = wrap(static_cast<long long>(fy), period_y), y1 = wrap(static_cast<long long>(fy) + 1, period_y);
  const float n00 = glm::dot(lattice_gradient(seed, x0, y0), glm::vec2(tx, ty));
  const float n10 = glm::dot(lattice_gradient(seed, x1, y0), glm::vec2(tx - 1.0f, ty));
  const float n01 = glm::dot(lattice_gradient(seed, x0, y1), glm::vec2(tx, ty - 1.0f));
  const float n11 = glm::dot(lattice_gradient(seed, x1, y1), glm::vec2(tx - 1.0f, ty - 1.0f));
  const float sx = fade(tx), sy = fade(ty);
  return glm::mix(glm::mix(n00, n10, sx), glm::mix(n01, n11, sx), sy);
}

float gradient1(std::uint64_t seed, double x, int period) {
  const double fx = std::floor(x);
  const float t = static_cast<float>(x - fx);
  const int x0 = wrap(static_cast<long long>(fx), period), x1 = wrap(static_cast<long long>(fx) + 1, period);
  const float g0 = 2.0f * unit(seed, x0, 0x31) - 1.0f, g1 = 2.0f * unit(seed, x1, 0x31) - 1.0f;
  return glm::mix(g0 * t, g1 * (t - 1.0f), fade(t));
}

float fbm(std::uint64_t seed, double u, double v, int cells, int octaves, float gain) {
  float sum = 0.0f, amplitude = 1.0f, total = 0.0f;
  int n = cells;
  for (int k = 0; k < octaves; ++k) {
    sum += amplitude * gradient(hash(seed, k), u * n, v * n, n, n);
    total += amplitude;
    amplitude *= gain;
    n *= 2;
  }
  // One octave spans about ±0.7; scale so the sum spans about ±1.
  return sum / (0.7f * total);
}

CellularHit cellular(std::uint64_t seed, double u, double v, int cells, float jitter) {
  const double x = u * cells, y = v * cells;
  const double cx = std::floor(x), cy = std::floor(y);
  CellularHit hit;
  hit.f1 = hit.f2 = std::numeric_limits<float>::max();
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const long long ix = static_cast<long long>(cx) + dx, iy = static_cast<long long>(cy) + dy;
      const int wx = wrap(ix, cells), wy = wrap(iy, cells);
      // The feature point of cell (wx, wy), placed in the unwrapped neighbour cell (ix, iy).
      // Both jitter coordinates from one hash: its top and its next 24 bits.
      const std::uint64_t h = hash(seed, wx, wy, 0xf1);
      const float jx = 0.5f + jitter * (unit(h) - 0.5f);
      const float jy = 0.5f + jitter * (unit(h << 24) - 0.5f);
      const glm::vec2 d(static_cast<float>(double(ix) + jx - x), static_cast<float>(double(iy) + jy - y));
      const float dist = glm::length(d);
      if (dist < hit.f1) {
        hit.f2 = hit.f1;
        hit.f1 = dist;
        hit.cell_x = wx;
        hit.cell_y = wy;
        hit.to_nearest = d;
      } else if (dist < hit.f2) {
        hit.f2 = dist;
      }
    }
  }
  return hit;
}

int cells_for(double length_mm, double feature_mm) {
  const long long n = std::llround(length_mm / feature_mm);
  return n < 1 ? 1 : static_cast<int>(n);
}

}  // namespace svbrdf::noise
