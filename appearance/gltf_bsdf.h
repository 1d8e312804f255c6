#pragma once
// The glTF 2.0 metallic-roughness BRDF (gltf.h, brdf-models.md) as a Bsdf. eval is gltf_eval.
// Sampling, a mix of two samplers chosen from wo alone (w0 = (1 − wo.z)^5 stands in for the
// Fresnel weight (1 − |wo·h|)^5):
//   specular share  s = mix(0.04 + 0.96·w0, max(base + (1 − base)·w0), metallic)
//     → wi = wo reflected about a GGX visible normal (α = gltf_alpha(roughness));
//   diffuse share   d = (1 − metallic)·max(base)·(1 − 0.04 − 0.96·w0)
//     → cosine-weighted;
// scatter probability min(1, s + d) (absorbed otherwise), shares s/(s+d) and d/(s+d).
#include "appearance/bsdf.h"
#include "appearance/gltf.h"

namespace svbrdf {

class GltfBsdf final : public Bsdf {
 public:
  explicit GltfBsdf(const GltfParams& p = {});
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override { return gltf_eval(p_, wi, wo); }
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;
  const GltfParams& params() const { return p_; }

 private:
  float specular_share(const glm::vec3& wo, float* p) const;
  GltfParams p_;
  float alpha_, base_max_;
};

}  // namespace svbrdf
