#include "appearance/microfacet.h"

#include <algorithm>
#include <cmath>

#include "appearance/fresnel.h"
#include "appearance/sampling.h"
#include "appearance/shading.h"

namespace svbrdf {

MicrofacetParams metal_plastic_params(MicrofacetParams base, float t, const Rgb& color) {
  base.fresnel = FresnelMode::schlick;
  base.kd = (1.0f - t) * color;
  base.f0 = glm::mix(Rgb(0.04f), color, t);
  return base;
}

Microfacet::Microfacet(const MicrofacetParams& p)
    : p_(p), dist_{p.distribution, p.alpha}, kd_max_(max_channel(p.kd)) {}

Rgb Microfacet::fresnel(float cos_i) const {
  switch (p_.fresnel) {
    case FresnelMode::schlick: return fresnel_schlick(p_.f0, cos_i);
    case FresnelMode::dielectric: return Rgb(fresnel_dielectric(cos_i, p_.ior));
    case FresnelMode::conductor: return fresnel_conductor(cos_i, p_.eta, p_.k);
    case FresnelMode::none: break;
  }
  return Rgb(1.0f);
}

Rgb Microfacet::eval(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  const glm::vec3 h = glm::normalize(wi + wo);
  const float g = p_.masking == Masking::smith ? dist_.g2(wi, wo, h) : vgroove_g(wi, wo, h);
  const float spec = dist_.d(h) * g / (4.0f * wi.z * wo.z);
  return p_.kd * kInvPi + fresnel(glm::dot(wi, h)) * spec;
}

float Microfacet::specular_share(const glm::vec3& wo, float* p) const {
  const float s = max_channel(fresnel(wo.z));
  const float sum = s + kd_max_;
  *p = std::min(1.0f, sum);
  return sum > 0 ? s / sum : 1.0f;
}

float Microfacet::scatter_probability(const glm::vec3& wo) const {
  if (wo.z <= 0) return 0.0f;
  float p;
  specular_share(wo, &p);
  return p;
}

BsdfSample Microfacet::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0) return {};
  float p;
  const float q_spec = specular_share(wo, &p);
  if (u.x >= p) return {};
  const glm::vec3 wi = u.x / p < q_spec ? reflect_about(wo, dist_.sample_visible(wo, {u.y, u.z}))
                                        : sample_cosine_hemisphere({u.y, u.z});
  if (wi.z <= 0) return {};
  return finite_sample(wi, pdf(wi, wo), eval(wi, wo));
}

float Microfacet::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0f;
  float p;
  const float q_spec = specular_share(wo, &p);
  return p * (q_spec * dist_.reflection_pdf(wi, wo) + (1.0f - q_spec) * wi.z * kInvPi);
}

}  // namespace svbrdf
