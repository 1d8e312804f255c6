#pragma once
// glTF cameras (§3.10): perspective (yfov, looking along local −Z, +Y up) and orthographic (ymag
// half height), placed by their node. Camera rays carry exact differentials — the rays through the
// next pixel to the right and below — from which each hit's texture footprint follows
// (Igehy 1999, "Tracing ray differentials"; pbrt-v4 §10.1).
//
// Depth of field: a thin lens (pbrt-v4 §5.2.3) of radius R, in scene units, in the plane through the
// camera's position across its view axis, focused on the plane at distance F along that axis. A ray
// leaves the lens at a point of the disk and passes through the point of the plane of focus that the
// pinhole ray of its film position reaches, so that plane is sharp and a point at depth d is spread
// over a disk of radius R·|d − F|/F on the plane at depth d, or R·|d − F|/(F·d) in the image plane at
// distance 1 (what the pixel size 2·tan(yfov/2)/height is measured in). glTF cameras carry neither a
// lens nor a focus distance; radius 0 (the default) is glTF's pinhole. The differentials are those
// of the same lens point aimed through the next pixels' points of the plane of focus (pbrt-v4's):
// a footprint is the pixel's, as the pinhole's, and the blur is integrated by the lens samples.
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
  // The largest lens radius and focus distance set_lens takes.
  static constexpr float kMaxLensLength = 1e15f;

  // The image's aspect comes from the resolution: perspective keeps yfov, orthographic keeps ymag.
  Camera(const CameraDesc& desc, int width, int height);

  // A camera framing an axis-aligned box from the +Z side (glTF's front), slightly above, for
  // scenes that bring no camera.
  static CameraDesc framing(const glm::vec3& lo, const glm::vec3& hi);

  // A thin lens of radius `lens_radius` (scene units; 0: the pinhole) focused at `focus_distance`
  // along the view axis (> 0). Throws svbrdf::Error (bad input) naming the option for values that are
  // negative, zero where they must not be, or not finite.
  void set_lens(float lens_radius, float focus_distance);
  bool has_lens() const { return lens_radius_ > 0.0f; }
  float lens_radius() const { return lens_radius_; }
  float focus_distance() const { return focus_; }

  // The ray through film position (x, y) in pixels from the top-left corner of the image
  // (x ∈ [0, width)), with its one-pixel differentials; `lens` is the point of the unit disk the ray
  // leaves the lens at (ignored by the pinhole).
  CameraRay generate(float x, float y, glm::vec2 lens = glm::vec2(0.0f)) const;
  // The ray alone, for renders that need no footprint.
  Ray ray(float x, float y, glm::vec2 lens = glm::vec2(0.0f)) const { return ray_at(x, y, lens); }

  // pbrt-v4's approximation for rays that did not come from the camera: the position differentials
  // that a camera ray reaching p would have on the plane through p with normal n.
  void approximate_dp(const glm::vec3& p, const glm::vec3& n, glm::vec3& dpdx, glm::vec3& dpdy) const;

  int width() const { return width_; }
  int height() const { return height_; }
  const glm::vec3& position() const { return position_; }
  const glm::vec3& forward() const { return forward_; }

 private:
  Ray ray_at(float x, float y, glm::vec2 lens) const;

  CameraDesc::Type type_;
  int width_, height_;
  glm::vec3 position_, right_, up_, forward_;  // orthonormal (node scale removed)
  float half_w_ = 1.0f, half_h_ = 1.0f;        // tan(fov/2)·aspect and tan(fov/2), or ortho half extents
  glm::vec3 dx_, dy_, corner_;                 // film (x, y) ↦ corner + x·dx + y·dy on the image plane
  float znear_ = 0.0f, zfar_ = 0.0f;
  float lens_radius_ = 0.0f, focus_ = 1.0f;
};

// Inline: every camera sample calls these, and a call returning the rays through memory cost the
// sample a store-forwarding stall on each read of them (bench/results/render.md).
inline Ray Camera::ray_at(float x, float y, glm::vec2 lens) const {
  const glm::vec3 q = corner_ + x * dx_ + y * dy_;
  Ray r;
  const bool perspective = type_ == CameraDesc::Type::perspective;
  if (lens_radius_ > 0.0f) {
    // From the lens point to where the pinhole ray meets the plane of focus; that point's distance
    // along the view axis is focus_, by which znear and zfar (distances along −Z) scale.
    const glm::vec3 l = lens_radius_ * (lens.x * right_ + lens.y * up_);
    const glm::vec3 d = (perspective ? q : forward_) * focus_ - l;
    const float len = std::sqrt(glm::dot(d, d));
    r.origin = (perspective ? position_ : position_ + q) + l;
    r.dir = d * (1.0f / len);
    const float scale = len / focus_;
    r.tnear = znear_ * scale;
    r.tfar = zfar_ > 0.0f ? zfar_ * scale : 3.4e38f;
  } else if (perspective) {
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

inline CameraRay Camera::generate(float x, float y, glm::vec2 lens) const {
  CameraRay cr;
  cr.ray = ray_at(x, y, lens);
  // The offset rays through (x + 1, y) and (x, y + 1), their directions left unnormalized: only
  // the lines matter (camera_dp intersects them with the tangent plane).
  if (lens_radius_ > 0.0f) {
    // The same lens point aimed at the next pixels' points of the plane of focus (pbrt-v4 §5.2.3).
    // Orthographic: those points and the lens point both move by one pixel, so the direction stays.
    const glm::vec3 l = cr.ray.origin;
    if (type_ == CameraDesc::Type::perspective) {
      const glm::vec3 q = corner_ + x * dx_ + y * dy_;
      cr.dx_origin = cr.dy_origin = l;
      cr.dx_dir = position_ + (q + dx_) * focus_ - l, cr.dy_dir = position_ + (q + dy_) * focus_ - l;
    } else {
      cr.dx_origin = l + dx_, cr.dy_origin = l + dy_;
      cr.dx_dir = cr.dy_dir = cr.ray.dir;
    }
  } else if (type_ == CameraDesc::Type::perspective) {
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
