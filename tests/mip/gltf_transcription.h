#pragma once
// What the layers' tests transcribe of glTF 2.0 Appendix B in double, independently of the code under
// test: the specular term's D and V.
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

}  // namespace svbrdf::gltf_transcription
