#pragma once
// A perfect mirror (CGPP §27.5): eval is 0 everywhere; one impulse from r(wo) with magnitude
// rho. The energy split picks it with probability min(1, max(rho)) and is absorbed otherwise.
#include "appearance/bsdf.h"

namespace svbrdf {

class Mirror final : public Bsdf {
 public:
  explicit Mirror(const Rgb& rho = Rgb(1.0f));
  Rgb eval(const glm::vec3&, const glm::vec3&) const override { return Rgb(0); }
  Impulses impulses_in(const glm::vec3& wo) const override;
  Impulses impulses_out(const glm::vec3& wi) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3&, const glm::vec3&) const override { return 0.0f; }
  float scatter_probability(const glm::vec3& wo) const override;

 private:
  Rgb rho_;
  float p_;
};

}  // namespace svbrdf
