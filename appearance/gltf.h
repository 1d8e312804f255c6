#pragma once
// The glTF 2.0 metallic-roughness BRDF (glTF 2.0 specification, Appendix B, current text with the
// height-correlated Smith visibility), exactly as ../shared/spec/brdf-models.md writes it:
//   α = max(roughness², 1e-3), D = GGX, V = height-correlated Smith over 4·|n·wi|·|n·wo|,
//   s = V·D, w = (1 − |wo·h|)^5,
//   dielectric = mix(base_color/π, s, 0.04 + 0.96·w), metal = s·(base_color + (1 − base_color)·w),
//   f = mix(dielectric, metal, metallic).
// This pure function is shared by the Bsdf model, the MIP reference and the renderer.
#include <glm/glm.hpp>

#include "appearance/bsdf.h"
#include "appearance/microfacet_distribution.h"
#include "appearance/shading.h"

namespace svbrdf {

struct GltfParams {
  Rgb base_color{0.8f};  // linear
  float metallic = 0.0f;
  float roughness = 0.5f;  // perceptual; α = roughness²
};

inline float gltf_alpha(float roughness) { return glm::max(roughness * roughness, 1e-3f); }

// The metallic-roughness layering (glTF 2.0 Appendix B; the KHR_materials_specular form): the
// dielectric's Fresnel fr weighted by `specular` over `base_layer` (what is below the specular
// layer: Lambert's ρ/π, or more), mixed by metallic with the metal's Fresnel `metal_fresnel` (Schlick
// on base_color, or KHR_materials_iridescence's), both times the specular term s = V·D. gltf_eval
// and the glTF surface BSDF (gltf_surface_bsdf.h) both compose their layers here.
inline Rgb gltf_layers(const Rgb& metal_fresnel, float metallic, const Rgb& base_layer, const Rgb& fr, float specular,
                       float s) {
  const Rgb dielectric = (1.0f - specular * max_channel(fr)) * base_layer + specular * fr * s;
  const Rgb metal = s * metal_fresnel;
  return glm::mix(dielectric, metal, metallic);
}

// f(wi, wo) in the frame whose z is the shading normal; 0 below either horizon.
inline Rgb gltf_eval(const GltfParams& p, const glm::vec3& wi, const glm::vec3& wo) {
  if (wi.z <= 0 || wo.z <= 0) return Rgb(0);
  const glm::vec3 h = glm::normalize(wi + wo);
  const float a = gltf_alpha(p.roughness), a2 = a * a;
  // h.z > 0 always here (both directions above the horizon); wi·h = wo·h > 0, so χ⁺ = 1.
  // D in the form without the 1 − cos² cancellation (microfacet_core.h).
  const float d = ggx_d(a, h);
  const float s = smith_ggx_visibility(a2, wi.z, wo.z) * d;
  const float w = schlick_weight(glm::abs(glm::dot(wo, h)));
  const float fd = 0.04f + 0.96f * w;
  return gltf_layers(p.base_color + (Rgb(1.0f) - p.base_color) * w, p.metallic, p.base_color * kInvPi, Rgb(fd), 1.0f, s);
}

}  // namespace svbrdf
