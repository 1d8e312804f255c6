#pragma once
// What the layers' tests transcribe of glTF 2.0 Appendix B and of KHR_materials_anisotropy in double,
// independently of the code under test: the specular term's D and V.
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

namespace svbrdf::gltf_transcription {

constexpr double kPi = 3.14159265358979323846;

// GGX D and the height-correlated Smith V of glTF 2.0 Appendix B at α = max(r², 1e-3) about n.
inline double ggx_vd(double roughness, const glm::dvec3& n, const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::dvec3 h = glm::normalize(wi + wo);
  const double a = std::max(roughness * roughness, 1e-3), a2 = a * a;
  const double nh = glm::dot(n, h), ni = glm::dot(n, wi), no = glm::dot(n, wo);
  const double d = nh > 0 ? a2 / (kPi * std::pow(nh * nh * (a2 - 1) + 1, 2)) : 0.0;
  const double v = 0.5 / (no * std::sqrt(a2 + (1 - a2) * ni * ni) + ni * std::sqrt(a2 + (1 - a2) * no * no));
  return d * v;
}

// KHR_materials_anisotropy's D_GGX_anisotropic and V_GGX_anisotropic (its "Implementation" section)
// in double, about the unit normal n: α_t along the direction `dir` of the tangent plane z = 0 (the glTF
// tangent and bitangent) projected onto n's tangent plane, α_b across it (b = n × t); the material's
// α_t = mix(α, 1, strength²) and α_b = α = max(r², 1e-3).
inline double anisotropic_vd_alphas(double at, double ab, const glm::dvec2& dir, const glm::dvec3& n,
                                    const glm::dvec3& wi, const glm::dvec3& wo) {
  const glm::dvec3 h = glm::normalize(wi + wo);
  const glm::dvec3 d(dir, 0.0);
  const glm::dvec3 t = glm::normalize(d - n * glm::dot(n, d)), b = glm::cross(n, t);
  const double nh = glm::dot(n, h), ni = glm::dot(n, wi), no = glm::dot(n, wo);
  if (nh <= 0) return 0.0;
  const double a2 = at * ab;
  const glm::dvec3 f(ab * glm::dot(t, h), at * glm::dot(b, h), a2 * nh);
  const double w2 = a2 / glm::dot(f, f);
  const double dd = a2 * w2 * w2 / kPi;
  const double gv = ni * glm::length(glm::dvec3(at * glm::dot(t, wo), ab * glm::dot(b, wo), no));
  const double gl = no * glm::length(glm::dvec3(at * glm::dot(t, wi), ab * glm::dot(b, wi), ni));
  return dd * 0.5 / (gv + gl);
}
inline double anisotropic_vd(double roughness, double strength, const glm::dvec2& dir, const glm::dvec3& n,
                             const glm::dvec3& wi, const glm::dvec3& wo) {
  const double ab = std::max(roughness * roughness, 1e-3), at = ab + (1 - ab) * strength * strength;
  return anisotropic_vd_alphas(at, ab, dir, n, wi, wo);
}

}  // namespace svbrdf::gltf_transcription
