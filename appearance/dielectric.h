#pragma once
// A smooth dielectric interface (CGPP §27.5), two-sided: the outside is z > 0, the inside (index
// `ior` relative to the outside) z < 0. For the viewing direction wo, with η = n(other side) /
// n(wo's side), impulses_in(wo) holds:
//   the reflection from r(wo), magnitude F (exact Fresnel at |wo.z|, total internal reflection 1);
//   the refraction from the Snell direction on the other side, magnitude (1 − F)/η² — radiance
//   crossing from medium a into medium b is scaled by (n_b / n_a)² (solid-angle compression).
// impulses_out(wi) is the same seen from the light's side (refraction magnitude (1 − F)·η², η taken
// from wi's side).
// The energy split picks reflection with probability F and refraction with 1 − F (never absorbs):
// weights 1 and 1/η².
#include "appearance/bsdf.h"

namespace svbrdf {

class Dielectric final : public Bsdf {
 public:
  explicit Dielectric(float ior = 1.5f);
  Rgb eval(const glm::vec3&, const glm::vec3&) const override { return Rgb(0); }
  Impulses impulses_in(const glm::vec3& wo) const override;
  Impulses impulses_out(const glm::vec3& wi) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3&, const glm::vec3&) const override { return 0.0f; }

 private:
  float ior_;
};

}  // namespace svbrdf
