#include "appearance/dielectric.h"

#include <cmath>

#include "appearance/fresnel.h"
#include "appearance/shading.h"

namespace svbrdf {

Dielectric::Dielectric(float ior) : ior_(ior) {}

// The Fresnel factor is the same seen from either side of a refracted pair (F(θ, η) =
// F(θt, 1/η)), so only the radiance scaling differs between the two queries: light crossing from
// medium a into medium b is scaled by (n_b / n_a)².
Impulses Dielectric::impulses_in(const glm::vec3& wo) const {
  Impulses out;
  if (wo.z == 0) return out;
  const float eta = wo.z > 0 ? ior_ : 1.0f / ior_;
  const float f = fresnel_dielectric(std::abs(wo.z), eta);
  out.add(mirror_direction(wo), Rgb(f));
  glm::vec3 t;
  if (f < 1.0f && refract_through(wo, eta, t)) out.add(t, Rgb((1.0f - f) / (eta * eta)));
  return out;
}

Impulses Dielectric::impulses_out(const glm::vec3& wi) const {
  Impulses out;
  if (wi.z == 0) return out;
  const float eta = wi.z > 0 ? ior_ : 1.0f / ior_;  // n(other side)/n(wi's side)
  const float f = fresnel_dielectric(std::abs(wi.z), eta);
  out.add(mirror_direction(wi), Rgb(f));
  glm::vec3 t;
  // Light from wi leaves toward t on the other side scaled by (1 − F)(n_t / n_wi)² = (1 − F) η².
  if (f < 1.0f && refract_through(wi, eta, t)) out.add(t, Rgb((1.0f - f) * eta * eta));
  return out;
}

BsdfSample Dielectric::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z == 0) return {};
  const float eta = wo.z > 0 ? ior_ : 1.0f / ior_;
  const float f = fresnel_dielectric(std::abs(wo.z), eta);
  glm::vec3 t;
  if (u.x < f || !refract_through(wo, eta, t)) return impulse_sample(mirror_direction(wo), f, Rgb(f));
  return impulse_sample(t, 1.0f - f, Rgb((1.0f - f) / (eta * eta)));
}

}  // namespace svbrdf
