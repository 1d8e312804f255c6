#pragma once
// Normal-map decoding as ../shared/spec/brdf-mip.md defines it (and glTF 2.0, "normalTexture"):
// n = normalize((2·rgb − 1)·(s, s, 1)) with normal scale s, tangent space, +Y up.
#include <glm/glm.hpp>

namespace svbrdf {

inline glm::vec3 decode_normal(const glm::vec3& rgb, float scale = 1.0f) {
  const glm::vec3 t = (2.0f * rgb - 1.0f) * glm::vec3(scale, scale, 1.0f);
  const float len2 = glm::dot(t, t);
  // A texel of (0.5, 0.5, 0.5) has no direction; the unperturbed normal is the only sensible reading.
  return len2 > 1e-12f ? t / std::sqrt(len2) : glm::vec3(0, 0, 1);
}

// The inverse for unit normals with z ≥ 0 (scale 1): what a normal-map writer stores.
inline glm::vec3 encode_normal(const glm::vec3& n) { return 0.5f * n + 0.5f; }

}  // namespace svbrdf
