#pragma once
// Direction sampling helpers in the local frame (z = normal), each with the density it produces
// (solid-angle measure). Used by the BSDF models and directly by the MIP and render modules.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

#include "appearance/frame.h"
#include "appearance/shading.h"

namespace svbrdf {

// Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square": [0,1)² → unit disk,
// area-preserving, so stratification of u survives.
inline glm::vec2 sample_concentric_disk(const glm::vec2& u) {
  const float a = 2.0f * u.x - 1.0f, b = 2.0f * u.y - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
  float r, phi;
  if (a * a > b * b) {
    r = a;
    phi = (kPi / 4.0f) * (b / a);
  } else {
    r = b;
    phi = (kPi / 2.0f) - (kPi / 4.0f) * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

// Cosine-weighted hemisphere (Malley's method: project the disk up), p = cosθ/π.
inline glm::vec3 sample_cosine_hemisphere(const glm::vec2& u) {
  const glm::vec2 d = sample_concentric_disk(u);
  const float z = std::sqrt(std::max(0.0f, 1.0f - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0 ? cos_theta * kInvPi : 0.0f; }

// Uniform on the unit sphere, p = 1/(4π).
inline glm::vec3 sample_uniform_sphere(const glm::vec2& u) {
  const float z = 1.0f - 2.0f * u.x;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = kTwoPi * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float kUniformSpherePdf = 0.25f * kInvPi;

// The normalized cosine-power lobe about z on the hemisphere z > 0: p = (n+1)/(2π)·cos^n θ
// (the Phong lobe sampler, CGPP §27.13 / Lafortune & Willems 1994). cosθ = u^(1/(n+1)); the
// sine comes from 1 − cosθ computed with expm1 so lobes up to n ~ 10^6 keep their width in floats.
inline glm::vec3 sample_power_cosine(const glm::vec2& u, float n) {
  const double log_u = std::log(std::max(static_cast<double>(u.x), 1e-300));
  const double one_minus_c = -std::expm1(log_u / (static_cast<double>(n) + 1.0));
  const double c = 1.0 - one_minus_c;
  const double s = std::sqrt(std::max(0.0, one_minus_c * (1.0 + c)));
  const double phi = 2.0 * kPiD * static_cast<double>(u.y);
  return {static_cast<float>(s * std::cos(phi)), static_cast<float>(s * std::sin(phi)), static_cast<float>(c)};
}
inline float power_cosine_pdf(float cos_theta, float n) {
  return cos_theta > 0 ? (n + 1.0f) * (0.5f * kInvPi) * std::pow(cos_theta, n) : 0.0f;
}

// The same lobe about a unit axis (e.g. the mirror direction r(wo)); its density is
// power_cosine_pdf(dot(axis, w), n).
inline glm::vec3 sample_power_cosine_about(const glm::vec3& axis, const glm::vec2& u, float n) {
  return Frame::from_normal(axis).to_world(sample_power_cosine(u, n));
}

}  // namespace svbrdf
