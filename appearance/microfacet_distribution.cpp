#include "appearance/microfacet_distribution.h"

#include <algorithm>
#include <cmath>

namespace svbrdf {
namespace {

const double kSqrtPi = std::sqrt(kPiD);

// Unnormalized CDF of the visible slope x for the α = 1 Beckmann surface seen from θ (incident
// direction in the xz plane): ∫_{−∞}^{x} (cosθ − t sinθ) exp(−t²)/√π dt
//   = cosθ (1 + erf x)/2 + sinθ exp(−x²)/(2√π)          (Heitz & d'Eon 2014, eq. 13's marginal).
double beckmann_slope_cdf(double x, double c, double s) {
  return 0.5 * c * (1.0 + std::erf(x)) + s * std::exp(-x * x) / (2.0 * kSqrtPi);
}

}  // namespace

float erf_inverse(float x) {
  x = std::clamp(x, -0.99999994f, 0.99999994f);
  // Giles 2010, single-precision branch pair.
  float w = -std::log((1.0f - x) * (1.0f + x));
  float p;
  if (w < 5.0f) {
    w -= 2.5f;
    p = 2.81022636e-08f;
    p = 3.43273939e-07f + p * w;
    p = -3.5233877e-06f + p * w;
    p = -4.39150654e-06f + p * w;
    p = 0.00021858087f + p * w;
    p = -0.00125372503f + p * w;
    p = -0.00417768164f + p * w;
    p = 0.246640727f + p * w;
    p = 1.50140941f + p * w;
  } else {
    w = std::sqrt(w) - 3.0f;
    p = -0.000200214257f;
    p = 0.000100950558f + p * w;
    p = 0.00134934322f + p * w;
    p = -0.00367342844f + p * w;
    p = 0.00573950773f + p * w;
    p = -0.0076224613f + p * w;
    p = 0.00943887047f + p * w;
    p = 1.00167406f + p * w;
    p = 2.83297682f + p * w;
  }
  // Two Newton steps on erf(y) = x in double: erf'(y) = 2/√π exp(−y²).
  double y = static_cast<double>(p) * static_cast<double>(x);
  for (int i = 0; i < 2; ++i) y -= (std::erf(y) - static_cast<double>(x)) * 0.5 * kSqrtPi * std::exp(y * y);
  return static_cast<float>(y);
}

glm::vec3 sample_beckmann_visible(float alpha, const glm::vec3& wo, const glm::vec2& u) {
  // Stretch to the α = 1 configuration: slopes scale by α, the view direction by (α, α, 1).
  const glm::dvec3 ws = glm::normalize(glm::dvec3(alpha * wo.x, alpha * wo.y, wo.z));
  const double ux = std::clamp(static_cast<double>(u.x), 1e-12, 1.0 - 1e-12);
  double sx, sy;
  if (ws.z > 0.999999) {
    // Normal view: all normals visible in proportion to D cos, i.e. the slope density
    // exp(−|s|²)/π itself: |s|² ~ Exp(1).
    const double r = std::sqrt(-std::log(1.0 - ux));
    const double phi = 2.0 * kPiD * u.y;
    sx = r * std::cos(phi);
    sy = r * std::sin(phi);
  } else {
    const double c = ws.z, s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const double cot = c / s;
    const double total = beckmann_slope_cdf(cot, c, s);
    const double target = ux * total;
    // Safeguarded Newton on CDF(x) = target over (lo, cot]: the CDF is increasing there.
    double lo = -9.0, hi = cot;
    double x = std::clamp(static_cast<double>(erf_inverse(static_cast<float>(2.0 * ux - 1.0))), lo, hi);
    for (int it = 0; it < 40; ++it) {
      const double err = beckmann_slope_cdf(x, c, s) - target;
      if (std::abs(err) <= 1e-9 * total) break;
      if (err > 0) hi = x; else lo = x;
      const double deriv = (c - x * s) * std::exp(-x * x) / kSqrtPi;
      double next = deriv > 0 ? x - err / deriv : 0.5 * (lo + hi);
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      if (hi - lo < 1e-12) break;
      x = next;
    }
    sx = x;
    sy = erf_inverse(static_cast<float>(2.0 * std::clamp(static_cast<double>(u.y), 1e-12, 1.0 - 1e-12) - 1.0));
    // Rotate from the frame in which the stretched view lies in the xz plane.
    const double r = std::sqrt(ws.x * ws.x + ws.y * ws.y);
    const double cphi = r > 0 ? ws.x / r : 1.0, sphi = r > 0 ? ws.y / r : 0.0;
    const double rx = cphi * sx - sphi * sy, ry = sphi * sx + cphi * sy;
    sx = rx;
    sy = ry;
  }
  // Unstretch the slopes and turn the slope (sx, sy) into the normal (−sx, −sy, 1)/|·|.
  return glm::vec3(glm::normalize(glm::dvec3(-alpha * sx, -alpha * sy, 1.0)));
}

}  // namespace svbrdf
