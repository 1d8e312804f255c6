#include "appearance/phong.h"

#include <algorithm>
#include <cmath>

#include "appearance/sampling.h"
#include "appearance/shading.h"

namespace svbrdf {

Phong::Phong(const Rgb& kd, const Rgb& ks, float n) : kd_(kd), ks_(ks), n_(n) {
  const float d = max_channel(kd), s = max_channel(ks);
  p_ = std::min(1.0f, d + s);
  q_diffuse_ = d + s > 0 ? d / (d + s) : 1.0f;
}

Rgb Phong::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  const float c = glm::dot(mirror_direction(wi), wo);
  const float lobe = c > 0 ? (n_ + 2.0f) * (0.5f * kInvPi) * std::pow(c, n_) : 0.0f;
  return kd_ * kInvPi + ks_ * lobe;
}

float Phong::scatter_probability(const glm::vec3& wo) const { return wo.z > 0 ? p_ : 0.0f; }

BsdfSample Phong::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0 || u.x >= p_) return {};
  const float v = u.x / p_;
  const glm::vec3 wi = v < q_diffuse_ ? sample_cosine_hemisphere({u.y, u.z})
                                      : sample_power_cosine_about(mirror_direction(wo), {u.y, u.z}, n_);
  if (wi.z <= 0) return {};
  return finite_sample(wi, pdf(wi, wo), eval(wi, wo));
}

float Phong::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0f;
  return p_ * (q_diffuse_ * wi.z * kInvPi +
               (1.0f - q_diffuse_) * power_cosine_pdf(glm::dot(mirror_direction(wo), wi), n_));
}

}  // namespace svbrdf
