#pragma once
// Oren & Nayar 1994, "Generalization of Lambert's Reflectance Model", the qualitative model
// (brdf-models.md): f = albedo/π (A + B max(0, cos(φi − φo)) sin α tan β),
// A = 1 − 0.5σ²/(σ² + 0.33), B = 0.45σ²/(σ² + 0.09), α = max(θi, θo), β = min(θi, θo).
// Sampled cosine-weighted; scatters with probability max(albedo) like Lambert.
#include "appearance/bsdf.h"

namespace svbrdf {

class OrenNayar final : public Bsdf {
 public:
  OrenNayar(const Rgb& albedo = Rgb(0.5f), float sigma = 0.3f);
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;

 private:
  Rgb albedo_;
  float a_, b_, p_;
};

}  // namespace svbrdf
