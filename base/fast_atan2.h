#pragma once
// atan2 in single precision without libm, for the renderer's per-sample direction → image mapping
// (the environment's radiance and pdf: two atan2 a sample, 7 % of a showcase frame through libm).
// atan(a) for a ∈ [0, 1] by an odd polynomial of degree 13 in a, fitted by iteratively reweighted
// least squares (Lawson's minimax) on Chebyshev nodes: within 2.5e-7 rad of atan there; the octant
// reduction adds float rounding (an ulp near π is 2.4e-7): within 6e-7 rad of std::atan2 everywhere
// (tests/mip/fast_atan2_test.cpp). Pixel lookups need 1e-4 rad for a 16k-wide image.
// atan2(0, 0) is 0, as std::atan2 gives for +0; NaN in, NaN out.
#include <cmath>

#include "base/math.h"

namespace svbrdf {

inline float fast_atan2(float y, float x) {
  constexpr float kHalfPi = 0.5f * kPi;
  const float ax = std::abs(x), ay = std::abs(y);
  const float hi = ax > ay ? ax : ay, lo = ax > ay ? ay : ax;
  const float a = hi == 0.0f ? 0.0f : lo / hi;  // ∈ [0, 1]; 0/0 avoided, NaN kept
  const float s = a * a;
  float r = a * (0.999996112f +
                 s * (-0.333173681f +
                      s * (0.198078156f + s * (-0.132333421f + s * (0.0796236716f + s * (-0.0336042194f + s * 0.00681179283f))))));
  r = ay > ax ? kHalfPi - r : r;
  r = std::signbit(x) ? kPi - r : r;
  return std::signbit(y) ? -r : r;
}

}  // namespace svbrdf
