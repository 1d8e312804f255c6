#include "appearance/mirror.h"

#include <algorithm>

#include "appearance/shading.h"

namespace svbrdf {

Mirror::Mirror(const Rgb& rho) : rho_(rho), p_(std::min(1.0f, max_channel(rho))) {}

Impulses Mirror::impulses_in(const glm::vec3& wo) const {
  Impulses out;
  if (wo.z > 0) out.add(mirror_direction(wo), rho_);
  return out;
}

// Reciprocal: light from wi leaves along r(wi) with the same magnitude.
Impulses Mirror::impulses_out(const glm::vec3& wi) const { return impulses_in(wi); }

float Mirror::scatter_probability(const glm::vec3& wo) const { return wo.z > 0 ? p_ : 0.0f; }

BsdfSample Mirror::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0 || u.x >= p_) return {};
  return impulse_sample(mirror_direction(wo), p_, rho_);
}

}  // namespace svbrdf
