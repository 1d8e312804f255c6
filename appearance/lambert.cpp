#include "appearance/lambert.h"

#include <algorithm>

#include "appearance/sampling.h"
#include "appearance/shading.h"

namespace svbrdf {

Lambert::Lambert(const Rgb& albedo) : albedo_(albedo), p_(std::min(1.0f, max_channel(albedo))) {}

Rgb Lambert::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  return albedo_ * kInvPi;
}

float Lambert::scatter_probability(const glm::vec3& wo) const { return wo.z > 0 ? p_ : 0.0f; }

BsdfSample Lambert::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0 || u.x >= p_) return {};
  const glm::vec3 wi = sample_cosine_hemisphere({u.y, u.z});
  if (wi.z <= 0) return {};
  return finite_sample(wi, p_ * wi.z * kInvPi, albedo_ * kInvPi);
}

float Lambert::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0f;
  return p_ * wi.z * kInvPi;
}

}  // namespace svbrdf
