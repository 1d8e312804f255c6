#pragma once
// Blinn–Phong in the CGPP ch. 14/27 normalization (brdf-models.md):
//   f = kl/π + kg (s+8)/(8π) max(0, h.z)^s,  h = normalize(wi + wo)
// (approximately energy-conserving when kl + kg ≤ 1; ~1.06 at grazing). Sampling: with
// probability max(kl) cosine-weighted, with probability max(kg) a half vector from the lobe
// (s+1)/(2π) cos^s θh about the normal reflected into wi (density p_h/(4 wo·h)); absorbed otherwise.
#include "appearance/bsdf.h"

namespace svbrdf {

class BlinnPhong final : public Bsdf {
 public:
  BlinnPhong(const Rgb& kl = Rgb(0.5f), const Rgb& kg = Rgb(0.5f), float s = 20.0f);
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;
  float exponent() const { return s_; }

 private:
  Rgb kl_, kg_;
  float s_;
  float p_, q_diffuse_;
};

}  // namespace svbrdf
