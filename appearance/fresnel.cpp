#include "appearance/fresnel.h"

#include <algorithm>
#include <cmath>
#include <complex>

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

FresnelPolarized fresnel_conductor_polarized(float cos_i, float eta, float k) {
  using C = std::complex<double>;
  const double ci = std::clamp(static_cast<double>(cos_i), 0.0, 1.0);
  const C n(eta, k);
  const C sin2_t = (1.0 - ci * ci) / (n * n);
  const C cos_t = std::sqrt(1.0 - sin2_t);
  const C rs = (ci - n * cos_t) / (ci + n * cos_t);
  const C rp = (n * ci - cos_t) / (n * ci + cos_t);
  return {static_cast<float>(std::norm(rs)), static_cast<float>(std::norm(rp))};
}

}  // namespace svbrdf
