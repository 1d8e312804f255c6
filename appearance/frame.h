#pragma once
// An orthonormal shading frame: z is the normal. BSDFs work in local coordinates (DESIGN.md,
// "Conventions"), so every hit point converts world directions with one of these.
#include <glm/glm.hpp>

namespace svbrdf {

struct Frame {
  glm::vec3 s{1, 0, 0};  // tangent
  glm::vec3 t{0, 1, 0};  // bitangent
  glm::vec3 n{0, 0, 1};  // normal

  // A frame around a unit normal with no preferred tangent. Duff et al. 2017, "Building an
  // Orthonormal Basis, Revisited" (JCGT 6(1)): branchless and continuous except at n.z = -0.
  static Frame from_normal(const glm::vec3& n);
  // A frame from a unit normal and an approximate tangent (Gram–Schmidt); falls back to
  // from_normal when the tangent is parallel to n.
  static Frame from_normal_tangent(const glm::vec3& n, const glm::vec3& tangent);

  glm::vec3 to_local(const glm::vec3& w) const { return {glm::dot(w, s), glm::dot(w, t), glm::dot(w, n)}; }
  glm::vec3 to_world(const glm::vec3& w) const { return s * w.x + t * w.y + n * w.z; }
};

}  // namespace svbrdf
