#pragma once
// Lambert (CGPP §27.7.1): f = albedo/π, sampled cosine-weighted; the energy split scatters with
// probability max(albedo) (the §27.14 example: albedo 0.2 → 20 % finite samples).
#include "appearance/bsdf.h"

namespace svbrdf {

class Lambert final : public Bsdf {
 public:
  explicit Lambert(const Rgb& albedo = Rgb(0.5f));
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;
  const Rgb& albedo() const { return albedo_; }

 private:
  Rgb albedo_;
  float p_;  // min(1, max channel of albedo)
};

}  // namespace svbrdf
