#pragma once
// Logarithms by the series of 2·atanh((m − 1)/(m + 1)) on the mantissa m ∈ [√½, √2) plus the
// exponent, for hot loops that need a few digits less than libm gives and cannot afford its call:
// the BRDF pyramid's merge cost (15 per candidate merge) and the MIP lookup's level (the release
// build targets SSE2, where log2 is a library call).
#include <cmath>
#include <cstdint>
#include <cstring>

namespace svbrdf {

// ln x for finite x > 0, within 1e-9 of std::log (the series to t⁹, |t| ≤ 0.172).
inline double series_log(double x) {
  if (!(x > 1e-300 && x < 1e300)) return std::log(x);
  std::uint64_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  int e = static_cast<int>((bits >> 52) & 0x7ff) - 1023;
  bits = (bits & 0x000fffffffffffffull) | 0x3ff0000000000000ull;
  double m;
  std::memcpy(&m, &bits, sizeof m);
  if (m > 1.4142135623730951) m *= 0.5, ++e;
  const double t = (m - 1) / (m + 1), t2 = t * t;
  return e * 0.69314718055994531 + 2 * t * (1 + t2 * (1.0 / 3 + t2 * (1.0 / 5 + t2 * (1.0 / 7 + t2 * (1.0 / 9)))));
}

// log₂ x for finite x ≥ 2^−126, within 2e-5, and exact at powers of two (the series to t⁷ on
// m ∈ [1, 2), |t| ≤ ⅓; exactness at m = 1 is what lets a footprint of 2^k texels select level k).
inline float series_log2(float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  const int e = static_cast<int>((bits >> 23) & 0xff) - 127;
  bits = (bits & 0x007fffffu) | 0x3f800000u;
  float m;
  std::memcpy(&m, &bits, sizeof m);
  const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
  return static_cast<float>(e) + 2.8853900817779268f * t * (1.0f + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7))));
}

}  // namespace svbrdf
