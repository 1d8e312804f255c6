#pragma once
// Microfacet normal distributions of CGPP §27.8 and brdf-models.md: GGX (Trowbridge–Reitz) and
// Beckmann, their Smith Λ and masking G1, the height-correlated G2, the Cook–Torrance V-groove
// masking, and sampling of the distribution of visible normals D_wo(h) with its density
// (Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs";
// Heitz & d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution of
// Visible Normals"). All directions in the local frame, z = macro normal; isotropic roughness α.
#include <glm/glm.hpp>

#include <cmath>

#include "appearance/microfacet_core.h"
#include "appearance/shading.h"

namespace svbrdf {

enum class MicrofacetType { ggx, beckmann };

// tan²θ of a direction (not necessarily unit) without the 1 − cos² cancellation near the pole.
inline float tan2_theta(const glm::vec3& w) { return (w.x * w.x + w.y * w.y) / (w.z * w.z); }

// GGX D (microfacet_core.h) for h not necessarily unit: α² |h|⁴ / (π (α² h.z² + h.x² + h.y²)²).
// D = 0 when h.z ≤ 0.
inline float ggx_d(float alpha, const glm::vec3& h) {
  if (h.z <= 0) return 0.0f;
  const float len2 = glm::dot(h, h);
  return len2 * len2 * ggx_d_terms(alpha * alpha, h.x * h.x + h.y * h.y, h.z * h.z);
}
// Λ_GGX(w) = (−1 + sqrt(1 + α² tan²θ)) / 2.
inline float ggx_lambda(float alpha, const glm::vec3& w) {
  if (w.z <= 0) return INFINITY;
  return 0.5f * (std::sqrt(1.0f + alpha * alpha * tan2_theta(w)) - 1.0f);
}

// Beckmann: D = exp(−tan²θh/α²) / (π α² cos⁴θh), 0 when h.z ≤ 0.
inline float beckmann_d(float alpha, const glm::vec3& h) {
  if (h.z <= 0) return 0.0f;
  const float a2 = alpha * alpha;
  const float c2 = h.z * h.z / glm::dot(h, h);
  return std::exp(-tan2_theta(h) / a2) * kInvPi / (a2 * c2 * c2);
}
// Λ_Beckmann(w) = (erf(a) − 1)/2 + exp(−a²)/(2a√π), a = 1/(α tanθ).
inline float beckmann_lambda(float alpha, const glm::vec3& w) {
  if (w.z <= 0) return INFINITY;
  const float t2 = tan2_theta(w);
  if (t2 == 0.0f) return 0.0f;
  const float a = 1.0f / (alpha * std::sqrt(t2));
  if (a > 9.0f) return 0.0f;  // erf(a) = 1 and exp(−a²) < 1e-35: Λ vanishes in float
  return 0.5f * (std::erf(a) - 1.0f) + std::exp(-a * a) / (2.0f * a * 1.7724538509055160273f);
}

// Cook & Torrance 1982 V-groove masking-shadowing: min(1, 2 h.z wo.z/(wo·h), 2 h.z wi.z/(wo·h)).
inline float vgroove_g(const glm::vec3& wi, const glm::vec3& wo, const glm::vec3& h) {
  const float oh = glm::dot(wo, h);
  if (oh <= 0 || glm::dot(wi, h) <= 0) return 0.0f;
  return std::min(1.0f, std::min(2.0f * h.z * wo.z / oh, 2.0f * h.z * wi.z / oh));
}

// Samples a GGX visible normal for the view direction wo (wo.z > 0). Stretch wo to the α = 1
// configuration, where the visible normals are those of a hemisphere: h_s = wo_s + a uniform
// direction on the spherical cap z > −wo_s.z (Dupuy & Benyoub 2023, "Sampling Visible GGX
// Normals with Spherical Caps"), then unstretch. Density: ggx_visible_pdf.
// The stretch is per axis, so the same construction samples anisotropic GGX (αx, αy).
inline glm::vec3 sample_ggx_visible(const glm::vec2& alpha, const glm::vec3& wo, const glm::vec2& u) {
  const glm::vec3 ws = glm::normalize(glm::vec3(alpha.x * wo.x, alpha.y * wo.y, wo.z));
  const float z = (1.0f - u.x) * (1.0f + ws.z) - ws.z;
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = kTwoPi * u.y;
  const glm::vec3 hs = glm::vec3(r * std::cos(phi), r * std::sin(phi), z) + ws;
  return glm::normalize(glm::vec3(alpha.x * hs.x, alpha.y * hs.y, std::max(hs.z, 1e-9f)));
}
inline glm::vec3 sample_ggx_visible(float alpha, const glm::vec3& wo, const glm::vec2& u) {
  return sample_ggx_visible(glm::vec2(alpha), wo, u);
}

// Anisotropic GGX with roughnesses α = (αx, αy) along the frame's x and y (KHR_materials_anisotropy;
// Heitz 2014, eq. 85 and 86): D = 1 / (π αx αy (hx²/αx² + hy²/αy² + hz²)²) for unit h, and
// Λ(w) = (−1 + √(1 + (αx² wx² + αy² wy²)/wz²)) / 2. With αx = αy they are ggx_d and ggx_lambda.
inline float ggx_d(const glm::vec2& alpha, const glm::vec3& h) {
  if (h.z <= 0) return 0.0f;
  const float x = h.x / alpha.x, y = h.y / alpha.y;
  const float q = (x * x + y * y + h.z * h.z) / glm::dot(h, h);
  return kInvPi / (alpha.x * alpha.y * q * q);
}
inline float ggx_lambda(const glm::vec2& alpha, const glm::vec3& w) {
  if (w.z <= 0) return INFINITY;
  const float x = alpha.x * w.x, y = alpha.y * w.y;
  return 0.5f * (std::sqrt(1.0f + (x * x + y * y) / (w.z * w.z)) - 1.0f);
}
// The height-correlated visibility G2 / (4 cosθi cosθo) = 1 / (4 cosθi cosθo (1 + Λ(wi) + Λ(wo))),
// both directions above the horizon.
inline float ggx_visibility(const glm::vec2& alpha, const glm::vec3& wi, const glm::vec3& wo) {
  return 0.25f / (wi.z * wo.z * (1.0f + ggx_lambda(alpha, wi) + ggx_lambda(alpha, wo)));
}

// The density of a visible normal: D_wo(h) = G1(wo) max(0, wo·h) D(h) / wo.z (Heitz 2014, eq. 2).
inline float ggx_visible_pdf(float alpha, const glm::vec3& wo, const glm::vec3& h) {
  const float oh = glm::dot(wo, h);
  if (wo.z <= 0 || oh <= 0) return 0.0f;
  return oh * ggx_d(alpha, h) / ((1.0f + ggx_lambda(alpha, wo)) * wo.z);
}
inline float beckmann_visible_pdf(float alpha, const glm::vec3& wo, const glm::vec3& h) {
  const float oh = glm::dot(wo, h);
  if (wo.z <= 0 || oh <= 0) return 0.0f;
  return oh * beckmann_d(alpha, h) / ((1.0f + beckmann_lambda(alpha, wo)) * wo.z);
}

// Samples a Beckmann visible normal for wo (wo.z > 0) by inverting the visible-slope CDF
// (Heitz & d'Eon 2014, §4). Defined in microfacet_distribution.cpp.
glm::vec3 sample_beckmann_visible(float alpha, const glm::vec3& wo, const glm::vec2& u);

// The inverse error function (Giles 2010, "Approximating the erfinv function", single precision,
// refined by Newton steps in double): the Beckmann visible-slope sampler's Gaussian slope.
float erf_inverse(float x);

struct MicrofacetDistribution {
  MicrofacetType type = MicrofacetType::ggx;
  float alpha = 0.3f;

  float d(const glm::vec3& h) const { return type == MicrofacetType::ggx ? ggx_d(alpha, h) : beckmann_d(alpha, h); }
  float lambda(const glm::vec3& w) const {
    return type == MicrofacetType::ggx ? ggx_lambda(alpha, w) : beckmann_lambda(alpha, w);
  }
  // Smith masking G1(w) = 1 / (1 + Λ(w)).
  float g1(const glm::vec3& w) const { return 1.0f / (1.0f + lambda(w)); }
  // Height-correlated Smith masking-shadowing G2 = χ⁺(wi·h) χ⁺(wo·h) / (1 + Λ(wi) + Λ(wo)).
  float g2(const glm::vec3& wi, const glm::vec3& wo, const glm::vec3& h) const {
    if (glm::dot(wi, h) <= 0 || glm::dot(wo, h) <= 0) return 0.0f;
    return 1.0f / (1.0f + lambda(wi) + lambda(wo));
  }
  // A visible normal h for wo (wo.z > 0), distributed as D_wo(h) = G1(wo) max(0, wo·h) D(h) / wo.z.
  glm::vec3 sample_visible(const glm::vec3& wo, const glm::vec2& u) const {
    return type == MicrofacetType::ggx ? sample_ggx_visible(alpha, wo, u) : sample_beckmann_visible(alpha, wo, u);
  }
  float visible_pdf(const glm::vec3& wo, const glm::vec3& h) const {
    const float oh = glm::dot(wo, h);
    if (wo.z <= 0 || oh <= 0) return 0.0f;
    return g1(wo) * oh * d(h) / wo.z;
  }
  // Density of wi = reflect_about(wo, h) for h ~ D_wo: D_wo(h) / (4 wo·h) = G1(wo) D(h) / (4 wo.z),
  // h = normalize(wi + wo). 0 when either direction is below the horizon.
  float reflection_pdf(const glm::vec3& wi, const glm::vec3& wo) const {
    if (wi.z <= 0 || wo.z <= 0) return 0.0f;
    const glm::vec3 h = glm::normalize(wi + wo);
    return g1(wo) * d(h) / (4.0f * wo.z);
  }
};

}  // namespace svbrdf
