#include "appearance/blinn_phong.h"

#include <algorithm>
#include <cmath>

#include "appearance/sampling.h"
#include "appearance/shading.h"

namespace svbrdf {

BlinnPhong::BlinnPhong(const Rgb& kl, const Rgb& kg, float s) : kl_(kl), kg_(kg), s_(s) {
  const float d = max_channel(kl), g = max_channel(kg);
  p_ = std::min(1.0f, d + g);
  q_diffuse_ = d + g > 0 ? d / (d + g) : 1.0f;
}

Rgb BlinnPhong::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  const glm::vec3 h = glm::normalize(wi + wo);
  const float lobe = h.z > 0 ? (s_ + 8.0f) * (0.125f * kInvPi) * std::pow(h.z, s_) : 0.0f;
  return kl_ * kInvPi + kg_ * lobe;
}

float BlinnPhong::scatter_probability(const glm::vec3& wo) const { return wo.z > 0 ? p_ : 0.0f; }

BsdfSample BlinnPhong::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0 || u.x >= p_) return {};
  const float v = u.x / p_;
  const glm::vec3 wi =
      v < q_diffuse_ ? sample_cosine_hemisphere({u.y, u.z}) : reflect_about(wo, sample_power_cosine({u.y, u.z}, s_));
  if (wi.z <= 0) return {};
  return finite_sample(wi, pdf(wi, wo), eval(wi, wo));
}

float BlinnPhong::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0f;
  const glm::vec3 h = glm::normalize(wi + wo);
  const float spec = power_cosine_pdf(h.z, s_) / (4.0f * glm::dot(wo, h));
  return p_ * (q_diffuse_ * wi.z * kInvPi + (1.0f - q_diffuse_) * spec);
}

}  // namespace svbrdf
