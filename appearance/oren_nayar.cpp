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
  // Written without branches on the directions (min, max and an exact arithmetic clamp), so that a
  // batch of unrelated pairs costs what a repeated one does: whether cos(φi − φo) < 0 and which angle
  // is larger are coin tosses a branch predictor loses on (bench/results/python.md).
  // cos(φi − φo) is taken as 0 when either direction is the normal.
  const float sin_product = sin_i * sin_o;
  const float cos_dphi = sin_product > 0 ? (wi.x * wo.x + wi.y * wo.y) / sin_product : 0.0f;
  // sin α tan β with α = max(θi, θo), β = min(θi, θo): sine and tangent increase on [0, π/2), so
  // sin α is the larger sine and tan β the smaller tangent.
  const float sin_alpha = std::max(sin_i, sin_o);
  const float tan_beta = std::min(sin_i / wi.z, sin_o / wo.z);
  // max(cos(φi − φo), 0) as arithmetic, exact: c + |c| is 2c or 0, and halving 2c is exact.
  const float cos_dphi_plus = 0.5f * (cos_dphi + std::fabs(cos_dphi));
  const float term = cos_dphi_plus * sin_alpha * tan_beta;
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
