#pragma once
// The microfacet BRDF of CGPP §27.8 (Cook & Torrance 1982; Walter et al. 2007), brdf-models.md:
//   f = kd/π + F(wi·h) D(h) G(wi, wo) / (4 wi.z wo.z),  h = normalize(wi + wo),
// D = GGX or Beckmann, G = height-correlated Smith or the Cook–Torrance V-groove, F = Schlick,
// exact dielectric, exact conductor or none. Sampling: the specular part by visible normals
// (reflect wo about h ~ D_wo), the kd part cosine-weighted; chosen in proportion to max F(wo.z)
// and max(kd), absorbed when their sum is below 1 (§27.14 energy split).
#include "appearance/bsdf.h"
#include "appearance/microfacet_distribution.h"

namespace svbrdf {

enum class Masking { smith, vgroove };
enum class FresnelMode { schlick, dielectric, conductor, none };

struct MicrofacetParams {
  MicrofacetType distribution = MicrofacetType::ggx;
  float alpha = 0.3f;
  Masking masking = Masking::smith;
  FresnelMode fresnel = FresnelMode::schlick;
  Rgb f0{0.04f};                     // schlick
  float ior = 1.5f;                  // dielectric
  Rgb eta{0.2f, 0.92f, 1.1f};        // conductor (gold-like defaults of brdf-models.md)
  Rgb k{3.9f, 2.45f, 2.14f};         // conductor
  Rgb kd{0.0f};                      // Lambertian term added
};

// The §27.12 human-scale control `metal_plastic` t ∈ [0, 1] over one `color`:
//   t = 0, plastic: kd = color (colored diffuse base), white Schlick highlight f0 = 0.04;
//   t = 1, metal: kd = 0, colored Schlick highlight f0 = color;
//   in between linearly: kd = (1 − t)·color, f0 = mix(0.04, color, t), fresnel = schlick.
// (The same blend as glTF's `metallic`, applied to the microfacet model's parameters.)
MicrofacetParams metal_plastic_params(MicrofacetParams base, float t, const Rgb& color);

class Microfacet final : public Bsdf {
 public:
  explicit Microfacet(const MicrofacetParams& p = {});
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;
  const MicrofacetParams& params() const { return p_; }
  Rgb fresnel(float cos_i) const;

 private:
  // Probability of the specular sampler among the two, given wo; sets *p to the scatter probability.
  float specular_share(const glm::vec3& wo, float* p) const;
  MicrofacetParams p_;
  MicrofacetDistribution dist_;
  float kd_max_;
};

}  // namespace svbrdf
