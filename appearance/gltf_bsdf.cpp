#include "appearance/gltf_bsdf.h"

#include <algorithm>
#include <cmath>

#include "appearance/microfacet_distribution.h"
#include "appearance/sampling.h"
#include "appearance/shading.h"

namespace svbrdf {

GltfBsdf::GltfBsdf(const GltfParams& p) : p_(p), alpha_(gltf_alpha(p.roughness)), base_max_(max_channel(p.base_color)) {}

float GltfBsdf::specular_share(const glm::vec3& wo, float* p) const {
  const float x = 1.0f - wo.z;
  const float w0 = (x * x) * (x * x) * x;
  const float fd = 0.04f + 0.96f * w0;
  const float fm = max_channel(p_.base_color + (Rgb(1.0f) - p_.base_color) * w0);
  const float s = fd + (fm - fd) * p_.metallic;
  const float d = (1.0f - p_.metallic) * base_max_ * (1.0f - fd);
  *p = std::min(1.0f, s + d);
  return s + d > 0 ? s / (s + d) : 1.0f;
}

float GltfBsdf::scatter_probability(const glm::vec3& wo) const {
  if (wo.z <= 0) return 0.0f;
  float p;
  specular_share(wo, &p);
  return p;
}

BsdfSample GltfBsdf::sample(const glm::vec3& wo, const SampleU& u) const {
  if (wo.z <= 0) return {};
  float p;
  const float q_spec = specular_share(wo, &p);
  if (u.x >= p) return {};
  const glm::vec3 wi = u.x / p < q_spec ? reflect_about(wo, sample_ggx_visible(alpha_, wo, {u.y, u.z}))
                                        : sample_cosine_hemisphere({u.y, u.z});
  if (wi.z <= 0) return {};
  return finite_sample(wi, pdf(wi, wo), eval(wi, wo));
}

float GltfBsdf::pdf(const glm::vec3& wi, const glm::vec3& wo) const {
  if (wi.z <= 0 || wo.z <= 0) return 0.0f;
  float p;
  const float q_spec = specular_share(wo, &p);
  const glm::vec3 h = glm::normalize(wi + wo);
  // G1(wo) D(h) / (4 wo.z), the density of wi reflected about a visible normal.
  const float spec = ggx_d(alpha_, h) / ((1.0f + ggx_lambda(alpha_, wo)) * 4.0f * wo.z);
  return p * (q_spec * spec + (1.0f - q_spec) * wi.z * kInvPi);
}

}  // namespace svbrdf
