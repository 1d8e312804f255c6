#pragma once
// The scattering of a glTF material at one point, behind the §27.14 interface (appearance/bsdf.h),
// in the local shading frame. The finite part is the glTF metallic-roughness BRDF of
// ../shared/spec/brdf-models.md (appearance/gltf.h's gltf_eval) generalized by the extensions:
//   KHR_materials_ior, KHR_materials_specular — the dielectric Fresnel term of fresnel_mix:
//     F0 = min(((ior − 1)/(ior + 1))²·specular_color, 1), fr = F0 + (1 − F0)·(1 − |wo·h|)^5,
//     dielectric = (1 − specular·max(fr))·base + specular·fr·V·D;
//   KHR_materials_diffuse_roughness — base's Lambertian ρ/π becomes the energy-preserving
//     Oren–Nayar (EON, Portsmouth, Kutz & Hill 2024) with roughness σ;
//   KHR_materials_transmission — a fraction `transmission` of base becomes a transmission impulse.
// With the extensions at their defaults (ior 1.5, specular 1, color 1, σ 0, transmission 0) it is
// gltf_eval exactly. Transmission is thin-walled (no KHR_materials_volume): the impulse continues
// straight through (wi = −wo) with magnitude (1 − metallic)·transmission·(1 − specular·max(fr))·
// base_color, fr at h = n; a rough transmissive surface is treated as smooth (documented limit).
#include "appearance/bsdf.h"

namespace svbrdf {

// The material's parameters at one point, textures applied (glTF §3.9: factors multiply textures;
// COLOR_0 multiplies base color).
struct ShadingParams {
  Rgb base_color{1.0f};  // linear
  float metallic = 0.0f;
  float roughness = 1.0f;  // perceptual
  Rgb emission{0.0f};      // radiance
  float ior = 1.5f;
  float specular = 1.0f;
  Rgb specular_color{1.0f};
  float transmission = 0.0f;
  float diffuse_roughness = 0.0f;
  bool unlit = false;
};

class SurfaceBsdf final : public Bsdf {
 public:
  explicit SurfaceBsdf(const ShadingParams& p);

  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  Impulses impulses_in(const glm::vec3& wo) const override;
  Impulses impulses_out(const glm::vec3& wi) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;

  bool has_impulse() const { return transmission_weight_ > 0.0f; }

 private:
  struct LobeChoice {
    float specular = 0, diffuse = 0, transmission = 0;  // probabilities, summing to 1 (or all 0)
  };
  LobeChoice choose(const glm::vec3& wo) const;
  Rgb transmission_magnitude(float cos_o) const;
  Rgb diffuse_f(const glm::vec3& wi, const glm::vec3& wo) const;

  ShadingParams p_;
  float alpha_;
  Rgb f0_;
  float transmission_weight_;
};

// EON's directional albedo of its single-scattering (FON) part, the fitted form of the paper's
// Listing 1 (error < 0.1 %), and the full EON BRDF.
float eon_fon_albedo(float mu, float r);
Rgb eon_eval(const Rgb& rho, float r, const glm::vec3& wi, const glm::vec3& wo);

}  // namespace svbrdf
