#pragma once
// Logarithms by the series of 2·atanh((m − 1)/(m + 1)) on the mantissa m ∈ [√½, √2) plus the
// exponent, and the exponential by its Taylor series after taking out a power of two, for hot loops
// that need a few digits less than libm gives and cannot afford its call: the BRDF pyramid's merge
// cost (15 per candidate merge), the MIP lookup's level and the lobes' shapes at every hit (the
// release build targets SSE2, where log2 is a library call).
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

// ln x in float for finite x ≥ 2^−126: within 5e-7 relative for x in (1, 2], 2.5e-7·max(1, |ln x|)
// elsewhere (series_log's series to t⁹, in float: the lobes' shapes at every hit, where the double
// division and series were a few percent of a lookup).
inline float series_logf(float x) {
  std::uint32_t bits;
  std::memcpy(&bits, &x, sizeof bits);
  int e = static_cast<int>((bits >> 23) & 0xff) - 127;
  bits = (bits & 0x007fffffu) | 0x3f800000u;
  float m;
  std::memcpy(&m, &bits, sizeof m);
  if (m > 1.41421356f) m *= 0.5f, ++e;
  const float t = (m - 1.0f) / (m + 1.0f), t2 = t * t;
  return static_cast<float>(e) * 0.693147181f + 2.0f * t * (1.0f + t2 * (1.0f / 3 + t2 * (1.0f / 5 + t2 * (1.0f / 7 + t2 * (1.0f / 9)))));
}

// log₂ x for finite x ≥ 2^−126, within 3e-5 (the series's 2e-5 plus the float's rounding of the
// exponent's part), and exact at powers of two (the series to t⁷ on
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

// e^x for x ∈ [−87, 88], within 4e-7 relative: e^x = 2^n·e^r with n = round(x/ln 2), |r| ≤ ln 2/2,
// e^r by its Taylor series to r⁶ (the r⁷ term is below 1.2e-7). Below −87 the result would be
// denormal: 0 is returned (what a renderer flushing denormals gets anyway).
inline float series_exp(float x) {
  if (!(x >= -87.0f)) return 0.0f;
  x = x < 88.0f ? x : 88.0f;
  const float y = x * 1.44269504088896341f;
  const int n = static_cast<int>(y + (y >= 0.0f ? 0.5f : -0.5f));  // round half away from zero
  const float r = x - static_cast<float>(n) * 0.693145751953125f - static_cast<float>(n) * 1.42860682030941723212e-6f;
  const float p = 1.0f + r * (1.0f + r * (0.5f + r * (1.0f / 6 + r * (1.0f / 24 + r * (1.0f / 120 + r * (1.0f / 720))))));
  const std::uint32_t bits = static_cast<std::uint32_t>(n + 127) << 23;
  float scale;
  std::memcpy(&scale, &bits, sizeof scale);
  return p * scale;
}

}  // namespace svbrdf
