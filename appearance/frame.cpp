#include "appearance/frame.h"

#include <cmath>

namespace svbrdf {

Frame Frame::from_normal(const glm::vec3& n) {
  const float sign = std::copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float b = n.x * n.y * a;
  Frame f;
  f.s = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
  f.t = {b, sign + n.y * n.y * a, -n.y};
  f.n = n;
  return f;
}

Frame Frame::from_normal_tangent(const glm::vec3& n, const glm::vec3& tangent) {
  const glm::vec3 s = tangent - n * glm::dot(n, tangent);
  const float len2 = glm::dot(s, s);
  if (!(len2 > 1e-12f)) return from_normal(n);
  Frame f;
  f.n = n;
  f.s = s / std::sqrt(len2);
  f.t = glm::cross(n, f.s);
  return f;
}

}  // namespace svbrdf
