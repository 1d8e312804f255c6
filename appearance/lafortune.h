#pragma once
// Lafortune et al. 1997, "Non-Linear Approximation of Reflectance Functions", with diagonal
// lobe matrices (brdf-models.md): f = kd/π + Σ_k rgb_k max(0, Cx wi.x wo.x + Cy wi.y wo.y + Cz wi.z wo.z)^n_k.
// Each lobe is a cosine-power lobe about the axis c_k = (Cx wo.x, Cy wo.y, Cz wo.z) of strength
// |c_k|^n_k, so it is sampled as (n+1)/(2π) cos^n about ĉ_k; the lobe is picked in proportion to
// max(rgb_k)·|c_k|^n_k·2π/(n_k+1) (its integral without the cosine: a weak estimate, the weight
// corrects), the diffuse term in proportion to max(kd); absorbed when their sum is below 1.
#include <vector>

#include "appearance/bsdf.h"

namespace svbrdf {

struct LafortuneLobe {
  glm::vec3 c{-1.0f, -1.0f, 1.0f};  // (Cx, Cy, Cz); (−1, −1, 1) is the Phong lobe about r(wi)
  float n = 20.0f;
  Rgb weight{1.0f};
};

class Lafortune final : public Bsdf {
 public:
  static constexpr int kMaxLobes = 8;
  explicit Lafortune(const Rgb& kd = Rgb(0.5f), std::vector<LafortuneLobe> lobes = {});
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;

 private:
  // Selection weights for wo: [0] the diffuse term, [1 + k] lobe k; returns their sum.
  float selection(const glm::vec3& wo, float* weights) const;
  float lobe_pdf(const glm::vec3& wi, const glm::vec3& wo, const float* weights, float sum) const;
  Rgb kd_;
  std::vector<LafortuneLobe> lobes_;
};

}  // namespace svbrdf
