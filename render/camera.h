#pragma once
// glTF cameras (§3.10): perspective (yfov, looking along local −Z, +Y up) and orthographic (ymag
// half height), placed by their node. Camera rays carry exact differentials — the rays through the
// next pixel to the right and below — from which each hit's texture footprint follows
// (Igehy 1999, "Tracing ray differentials"; pbrt-v4 §10.1).
#include <cmath>

#include <glm/glm.hpp>

#include "gltf/scene.h"

namespace svbrdf {

struct Ray {
  glm::vec3 origin{0.0f};
  glm::vec3 dir{0.0f, 0.0f, -1.0f};  // unit
  float tnear = 0.0f;
  float tfar = 3.4e38f;
};

// A camera ray with its differentials in x and y: the rays one pixel apart (directions not
// necessarily unit).
struct CameraRay {
  Ray ray;
  glm::vec3 dx_origin{0.0f}, dx_dir{0.0f};
  glm::vec3 dy_origin{0.0f}, dy_dir{0.0f};
};

class Camera {
 public:
  // The image's aspect comes from the resolution: perspective keeps yfov, orthographic keeps ymag.
  Camera(const CameraDesc& desc, int width, int height);

  // A camera framing an axis-aligned box from the +Z side (glTF's front), slightly above, for
  // scenes that bring no camera.
  static CameraDesc framing(const glm::vec3& lo, const glm::vec3& hi);

  // The ray through film position (x, y) in pixels from the top-left corner of the image
  // (x ∈ [0, width)), with its one-pixel differentials.
  CameraRay generate(float x, float y) const;
  // The ray alone, for renders that need no footprint.
  Ray ray(float x, float y) const { return ray_at(x, y); }

  // pbrt-v4's approximation for rays that did not come from the camera: the position differentials
  // that a camera ray reaching p would have on the plane through p with normal n.
  void approximate_dp(const glm::vec3& p, const glm::vec3& n, glm::vec3& dpdx, glm::vec3& dpdy) const;

  int width() const { return width_; }
  int height() const { return height_; }
  const glm::vec3& position() const { return position_; }
  const glm::vec3& forward() const { return forward_; }

 private:
  Ray ray_at(float x, float y) const;

  CameraDesc::Type type_;
  int width_, height_;
  glm::vec3 position_, right_, up_, forward_;  // orthonormal (node scale removed)
  float half_w_ = 1.0f, half_h_ = 1.0f;        // tan(fov/2)·aspect and tan(fov/2), or ortho half extents
  glm::vec3 dx_, dy_, corner_;                 // film (x, y) ↦ corner + x·dx + y·dy on the image plane
  float znear_ = 0.0f, zfar_ = 0.0f;
};

// Inline: every camera sample calls these, and a call returning the rays through memory cost the
// sample a store-forwarding stall on each read of them (bench/results/render.md).
inline Ray Camera::ray_at(float x, float y) const {
  const glm::vec3 q = corner_ + x * dx_ + y * dy_;
  Ray r;
  if (type_ == CameraDesc::Type::perspective) {
    const float len = std::sqrt(glm::dot(q, q));
    r.origin = position_;
    r.dir = q * (1.0f / len);
    // znear/zfar are distances along −Z; along this ray they scale by len.
    r.tnear = znear_ * len;
    r.tfar = zfar_ > 0.0f ? zfar_ * len : 3.4e38f;
  } else {
    r.origin = position_ + q;
    r.dir = forward_;
    r.tnear = znear_;
    r.tfar = zfar_ > 0.0f ? zfar_ : 3.4e38f;
  }
  return r;
}

inline CameraRay Camera::generate(float x, float y) const {
  CameraRay cr;
  cr.ray = ray_at(x, y);
  // The offset rays through (x + 1, y) and (x, y + 1), their directions left unnormalized: only
  // the lines matter (camera_dp intersects them with the tangent plane).
  if (type_ == CameraDesc::Type::perspective) {
    const glm::vec3 q = corner_ + x * dx_ + y * dy_;
    cr.dx_origin = cr.dy_origin = position_;
    cr.dx_dir = q + dx_, cr.dy_dir = q + dy_;
  } else {
    cr.dx_origin = cr.ray.origin + dx_, cr.dy_origin = cr.ray.origin + dy_;
    cr.dx_dir = cr.dy_dir = forward_;
  }
  return cr;
}

}  // namespace svbrdf
