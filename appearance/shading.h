#pragma once
// Small geometric helpers of the local shading frame (z = normal) shared by the models:
// the mirror direction r(w) of brdf-models.md, reflection about a microfacet normal,
// Snell refraction (CGPP §27.5 / eq. 26.5 in vector form).
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>

#include "appearance/bsdf.h"
#include "base/math.h"

namespace svbrdf {

inline float max_channel(const Rgb& c) { return std::max(c.x, std::max(c.y, c.z)); }

// r(w) = (-w.x, -w.y, w.z): the mirror direction about the normal.
inline glm::vec3 mirror_direction(const glm::vec3& w) { return {-w.x, -w.y, w.z}; }

// w reflected about the unit vector m: 2(w·m)m − w.
inline glm::vec3 reflect_about(const glm::vec3& w, const glm::vec3& m) { return 2.0f * glm::dot(w, m) * m - w; }

// Refraction of w (pointing away from the surface on its side) through the plane z = 0 with the
// relative index eta = n(other side) / n(w's side). Returns false on total internal reflection.
// The result points away from the surface on the other side (Snell: sinθt = sinθ / eta).
inline bool refract_through(const glm::vec3& w, float eta, glm::vec3& out) {
  const float cos_i = std::abs(w.z);
  const float sin2_t = std::max(0.0f, 1.0f - cos_i * cos_i) / (eta * eta);
  if (sin2_t >= 1.0f) return false;
  const float cos_t = std::sqrt(1.0f - sin2_t);
  out = glm::vec3(-w.x / eta, -w.y / eta, w.z > 0 ? -cos_t : cos_t);
  return true;
}

// A finite sample whose weight is f·|wi.z| / pdf (§27.14); absorbed when the density is zero.
inline BsdfSample finite_sample(const glm::vec3& wi, float pdf, const Rgb& f) {
  BsdfSample s;
  if (!(pdf > 0)) return s;
  s.wi = wi;
  s.pdf = pdf;
  s.weight = f * (std::abs(wi.z) / pdf);
  s.kind = SampleKind::finite;
  return s;
}
// An impulse chosen with probability `probability`: weight = magnitude / probability.
inline BsdfSample impulse_sample(const glm::vec3& wi, float probability, const Rgb& magnitude) {
  BsdfSample s;
  if (!(probability > 0)) return s;
  s.wi = wi;
  s.pdf = probability;
  s.weight = magnitude / probability;
  s.kind = SampleKind::impulse;
  return s;
}

}  // namespace svbrdf
