#include "appearance/conductor_mirror.h"

#include <algorithm>

#include "appearance/fresnel.h"
#include "appearance/shading.h"

namespace svbrdf {

ConductorMirror::ConductorMirror(const Rgb& eta, const Rgb& k) : eta_(eta), k_(k) {}

Impulses ConductorMirror::impulses_in(const glm::vec3& wo) const {
  Impulses out;
  if (wo.z > 0) out.add(mirror_direction(wo), fresnel_conductor(wo.z, eta_, k_));
  return out;
}

Impulses ConductorMirror::impulses_out(const glm::vec3& wi) const { return impulses_in(wi); }

float ConductorMirror::scatter_probability(const glm::vec3& wo) const {
  return wo.z > 0 ? std::min(1.0f, max_channel(fresnel_conductor(wo.z, eta_, k_))) : 0.0f;
}

BsdfSample ConductorMirror::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0) return {};
  const Rgb f = fresnel_conductor(wo.z, eta_, k_);
  const float p = std::min(1.0f, max_channel(f));
  if (u.x >= p) return {};
  return impulse_sample(mirror_direction(wo), p, f);
}

}  // namespace svbrdf
