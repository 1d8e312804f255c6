#include "appearance/fresnel.h"

#include <algorithm>
#include <cmath>

namespace svbrdf {

FresnelPolarized fresnel_dielectric_polarized(float cos_i, float eta) {
  cos_i = std::clamp(cos_i, 0.0f, 1.0f);
  const float sin2_t = (1.0f - cos_i * cos_i) / (eta * eta);  // Snell
  if (sin2_t >= 1.0f) return {1.0f, 1.0f};                     // total internal reflection
  const float cos_t = std::sqrt(1.0f - sin2_t);
  const float rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const float rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return {rs * rs, rp * rp};
}

// The complex-index equations in real arithmetic (Born & Wolf §14.2; the form CGPP's references
// use): with s² = sin²θ, t = η² − κ² − s², a² + b² = sqrt(t² + 4η²κ²), a = sqrt((a² + b² + t)/2),
//   R_s = (a² + b² − 2a cosθ + cos²θ) / (a² + b² + 2a cosθ + cos²θ),
//   R_p = R_s (cos²θ (a² + b²) − 2a cosθ s² + s⁴) / (cos²θ (a² + b²) + 2a cosθ s² + s⁴).
// Cheaper than complex division (this runs per channel per shading point); the tests compare it
// with the complex form.
FresnelPolarized fresnel_conductor_polarized(float cos_i, float eta, float k) {
  const float c = std::clamp(cos_i, 0.0f, 1.0f), c2 = c * c, s2 = 1.0f - c2;
  const float eta2 = eta * eta, k2 = k * k;
  const float t = eta2 - k2 - s2;
  const float ab2 = std::sqrt(t * t + 4.0f * eta2 * k2);
  const float a = std::sqrt(std::max(0.0f, 0.5f * (ab2 + t)));
  const float rs = (ab2 + c2 - 2.0f * a * c) / (ab2 + c2 + 2.0f * a * c);
  const float p = c2 * ab2 + s2 * s2, q = 2.0f * a * c * s2;
  const float rp = rs * (p - q) / (p + q);
  return {rs, rp};
}

}  // namespace svbrdf
