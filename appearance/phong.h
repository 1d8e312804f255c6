#pragma once
// The normalized (modified) Phong BRDF (CGPP §27.7.2; Lewis 1994):
//   f = kd/π + ks (n+2)/(2π) max(0, r(wi)·wo)^n   (energy-conserving when kd + ks ≤ 1).
// The lobe is cut off where r(wi)·wo ≤ 0 for every n (also n = 0). Sampling: with probability
// max(kd) cosine-weighted, with probability max(ks) the cosine-power lobe (n+1)/(2π) cos^n about
// r(wo); absorbed otherwise (probabilities renormalized when max(kd) + max(ks) > 1).
#include <cmath>

#include "appearance/bsdf.h"

namespace svbrdf {

// The human-scale control of §27.12: shininess = log10 of the exponent, 0 (broad) ... 6 (very shiny).
inline float exponent_from_shininess(float shininess) { return std::pow(10.0f, shininess); }

class Phong final : public Bsdf {
 public:
  Phong(const Rgb& kd = Rgb(0.5f), const Rgb& ks = Rgb(0.5f), float n = 20.0f);
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;
  float exponent() const { return n_; }

 private:
  Rgb kd_, ks_;
  float n_;
  float p_, q_diffuse_;  // scatter probability; share of it that goes to the diffuse sampler
};

}  // namespace svbrdf
