#include "appearance/oren_nayar.h"

#include <algorithm>
#include <cmath>

#include "appearance/sampling.h"
#include "appearance/shading.h"

namespace svbrdf {

OrenNayar::OrenNayar(const Rgb& albedo, float sigma)
    : albedo_(albedo),
      a_(1.0f - 0.5f * sigma * sigma / (sigma * sigma + 0.33f)),
      b_(0.45f * sigma * sigma / (sigma * sigma + 0.09f)),
      p_(std::min(1.0f, max_channel(albedo))) {}

Rgb OrenNayar::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  const float sin_i = std::sqrt(std::max(0.0f, wi.x * wi.x + wi.y * wi.y));
  const float sin_o = std::sqrt(std::max(0.0f, wo.x * wo.x + wo.y * wo.y));
  float term = 0.0f;
  if (sin_i > 0 && sin_o > 0) {  // cos(φi − φo) is taken as 0 when either direction is the normal
    const float cos_dphi = (wi.x * wo.x + wi.y * wo.y) / (sin_i * sin_o);
    if (cos_dphi > 0) {
      // sin α tan β with α = max(θi, θo), β = min(θi, θo): the larger angle has the smaller cosine.
      const bool i_larger = wi.z < wo.z;
      const float sin_alpha = i_larger ? sin_i : sin_o;
      const float tan_beta = i_larger ? sin_o / wo.z : sin_i / wi.z;
      term = cos_dphi * sin_alpha * tan_beta;
    }
  }
  return albedo_ * (kInvPi * (a_ + b_ * term));
}

float OrenNayar::scatter_probability(const glm::vec3& wo) const { return wo.z > 0 ? p_ : 0.0f; }

BsdfSample OrenNayar::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0 || u.x >= p_) return {};
  const glm::vec3 wi = sample_cosine_hemisphere({u.y, u.z});
  if (wi.z <= 0) return {};
  return finite_sample(wi, p_ * wi.z * kInvPi, eval(wi, wo));
}

float OrenNayar::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0f;
  return p_ * wi.z * kInvPi;
}

}  // namespace svbrdf
