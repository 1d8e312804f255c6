#pragma once
// The GGX microfacet terms every glTF BRDF in the project is built from, once, in any precision:
// the appearance models (float), the renderer's surface BSDF (float), and the MIP's lobes and exact
// reference (float and double).
//   D_GGX(h) = α² / (π·(sin²θh + cos²θh·α²)²)              (Walter et al. 2007, eq. 33)
//   V(wi, wo) = G2 / (4·cosθi·cosθo)
//             = 0.5 / (cosθo·√(α² + (1 − α²)·cos²θi) + cosθi·√(α² + (1 − α²)·cos²θo))
//   the height-correlated Smith masking-shadowing of GGX over the two cosines (Heitz 2014,
//   "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs", eq. 99; the form
//   the glTF 2.0 specification, Appendix B, writes).
//   Schlick's Fresnel weight (1 − cosθ)^5 (Schlick 1994).
// Writing 1 − cos²θh as |n × h|² keeps the peak of sharp lobes precise: the plain form loses up to
// 3 % there in float for α near 1e-3.
#include <cmath>

#include "base/math.h"

namespace svbrdf {

// D_GGX from α², |n × h|² and (n·h)², with h not necessarily unit: multiply by |h|⁴ for that.
template <class T>
T ggx_d_terms(T alpha2, T sin2, T cos2) {
  const T q = sin2 + cos2 * alpha2;
  return alpha2 * kInvPiOf<T> / (q * q);
}

// One side of the height-correlated visibility: √(α² + (1 − α²)·cos²θ).
template <class T>
T smith_ggx_root(T alpha2, T cos_theta) {
  return std::sqrt(alpha2 + (T(1) - alpha2) * cos_theta * cos_theta);
}

// V = G2 / (4·cosθi·cosθo), both cosines positive.
template <class T>
T smith_ggx_visibility(T alpha2, T cos_i, T cos_o) {
  return T(0.5) / (cos_o * smith_ggx_root(alpha2, cos_i) + cos_i * smith_ggx_root(alpha2, cos_o));
}

// Schlick's weight w = (1 − c)^5 for c = |wo·h|.
template <class T>
T schlick_weight(T cos_theta) {
  const T x = T(1) - cos_theta, x2 = x * x;
  return x2 * x2 * x;
}

}  // namespace svbrdf
