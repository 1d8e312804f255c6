#include "render/camera.h"

#include <algorithm>
#include <cmath>

#include "base/error.h"

namespace svbrdf {

Camera::Camera(const CameraDesc& d, int width, int height) : type_(d.type), width_(width), height_(height) {
  const glm::dmat4& m = d.to_world;
  position_ = glm::vec3(m * glm::dvec4(0, 0, 0, 1));
  // Orthonormalize the node's axes: glTF camera nodes should not scale, but a scale must not skew rays.
  const glm::dvec3 f = -glm::normalize(glm::dvec3(m[2]));
  glm::dvec3 up = glm::dvec3(m[1]);
  glm::dvec3 r = glm::cross(f, up);
  if (glm::length(r) < 1e-12) r = glm::dvec3(m[0]);
  r = glm::normalize(r);
  up = glm::normalize(glm::cross(r, f));
  forward_ = glm::vec3(f), right_ = glm::vec3(r), up_ = glm::vec3(up);
  const float aspect = float(width) / float(height);
  if (type_ == CameraDesc::Type::perspective) {
    half_h_ = std::tan(0.5f * d.yfov);
    half_w_ = half_h_ * aspect;
  } else {
    half_h_ = d.ymag;
    half_w_ = d.ymag * aspect;
  }
  znear_ = d.znear;
  zfar_ = d.zfar;
  // The image plane at distance 1 along forward (perspective) or through the eye (orthographic).
  dx_ = right_ * (2.0f * half_w_ / float(width_));
  dy_ = -up_ * (2.0f * half_h_ / float(height_));
  corner_ = right_ * -half_w_ + up_ * half_h_ + (type_ == CameraDesc::Type::perspective ? forward_ : glm::vec3(0.0f));
  // The reader checks each number; this checks what they make together, so that no ray the camera
  // generates is NaN or infinite (Embree asserts on those).
  const glm::vec3 far_corner = corner_ + dx_ * float(width_) + dy_ * float(height_);
  if (!std::isfinite(glm::dot(position_, position_)) || !std::isfinite(glm::dot(far_corner, far_corner)) ||
      !std::isfinite(glm::dot(corner_, corner_)) || !std::isfinite(half_w_ * half_h_))
    throw input_error(d.name, "the camera's placement and extent give rays that are not finite numbers");
}

void Camera::set_lens(float lens_radius, float focus_distance) {
  // Up to kMaxLensLength, so that a ray's direction before normalization (lengths of both) squares to
  // a finite float: Embree asserts on a NaN.
  if (!(lens_radius >= 0.0f && lens_radius <= kMaxLensLength))
    throw input_error("--aperture", "the lens radius must be a number in [0, 1e15]");
  if (!(focus_distance > 0.0f && focus_distance <= kMaxLensLength))
    throw input_error("--focus-distance", "the focus distance must be a number in (0, 1e15]");
  lens_radius_ = lens_radius;
  focus_ = focus_distance;
}

CameraDesc Camera::framing(const glm::vec3& lo, const glm::vec3& hi) {
  CameraDesc d;
  d.name = "framing";
  d.type = CameraDesc::Type::perspective;
  d.yfov = glm::radians(40.0f);
  const glm::vec3 center = 0.5f * (lo + hi);
  const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
  const float dist = 1.15f * radius / std::sin(0.5f * d.yfov);
  const glm::vec3 dir = glm::normalize(glm::vec3(0.0f, 0.35f, 1.0f));  // from the front, a little above
  const glm::vec3 eye = center + dir * dist;
  const glm::vec3 f = -dir, r = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0))), u = glm::cross(r, f);
  glm::dmat4 m(1.0);
  m[0] = glm::dvec4(glm::dvec3(r), 0);
  m[1] = glm::dvec4(glm::dvec3(u), 0);
  m[2] = glm::dvec4(glm::dvec3(-f), 0);
  m[3] = glm::dvec4(glm::dvec3(eye), 1);
  d.to_world = m;
  d.znear = 0.0f;
  return d;
}

void Camera::approximate_dp(const glm::vec3& p, const glm::vec3& n, glm::vec3& dpdx, glm::vec3& dpdy) const {
  // The camera's one-pixel offsets at the image centre, applied to a camera ray aimed at p.
  glm::vec3 o, d, ox, dx, oy, dy;
  if (type_ == CameraDesc::Type::perspective) {
    o = ox = oy = position_;
    const glm::vec3 to_p = p - position_;
    const float dist = glm::length(to_p);
    d = dist > 0.0f ? to_p / dist : forward_;
    const float px = 2.0f * half_w_ / float(width_), py = 2.0f * half_h_ / float(height_);
    dx = d + right_ * px;  // only the lines matter: no need to normalize
    dy = d - up_ * py;
  } else {
    d = dx = dy = forward_;
    o = p - forward_;
    ox = o + right_ * (2.0f * half_w_ / float(width_));
    oy = o - up_ * (2.0f * half_h_ / float(height_));
  }
  auto on_plane = [&](const glm::vec3& ro, const glm::vec3& rd) {
    const float denom = glm::dot(n, rd);
    if (std::abs(denom) < 1e-8f) return p;
    return ro + rd * (glm::dot(n, p - ro) / denom);
  };
  dpdx = on_plane(ox, dx) - p;
  dpdy = on_plane(oy, dy) - p;
}

}  // namespace svbrdf
