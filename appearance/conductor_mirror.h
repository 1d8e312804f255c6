#pragma once
// A smooth conductor (CGPP §27.5): one impulse from r(wo) with the exact conductor Fresnel
// reflectance F(wo.z; η + iκ) per channel as magnitude; chosen with probability min(1, max F).
#include "appearance/bsdf.h"

namespace svbrdf {

class ConductorMirror final : public Bsdf {
 public:
  ConductorMirror(const Rgb& eta = Rgb(0.2f, 0.92f, 1.1f), const Rgb& k = Rgb(3.9f, 2.45f, 2.14f));
  Rgb eval(const glm::vec3&, const glm::vec3&) const override { return Rgb(0); }
  Impulses impulses_in(const glm::vec3& wo) const override;
  Impulses impulses_out(const glm::vec3& wi) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3&, const glm::vec3&) const override { return 0.0f; }
  float scatter_probability(const glm::vec3& wo) const override;

 private:
  Rgb eta_, k_;
};

}  // namespace svbrdf
