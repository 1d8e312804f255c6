#pragma once
// The scattering of a glTF material at one point, behind the §27.14 interface (appearance/bsdf.h),
// in the local shading frame (z = the base's shading normal, x = the glTF tangent made orthogonal
// to it, y = N × T). The finite part is the glTF metallic-roughness BRDF of
// ../shared/spec/brdf-models.md (appearance/gltf.h's gltf_eval) with the layers of the extensions,
// composed as their specifications compose them, inside out:
//   KHR_materials_ior, KHR_materials_specular — the dielectric Fresnel term of fresnel_mix:
//     F0 = min(((ior − 1)/(ior + 1))²·specular_color, 1), fr = F0 + (1 − F0)·(1 − |wo·h|)^5,
//     dielectric = (1 − specular·max(fr))·base + specular·fr·V·D;
//   KHR_materials_diffuse_roughness — base's Lambertian ρ/π becomes the energy-preserving
//     Oren–Nayar (EON, appearance/eon.h) with roughness σ;
//   KHR_materials_transmission — base becomes mix(base, specular_btdf·base_color, transmission): on
//     a thin-walled surface (no volume) the extension's microfacet BTDF ("Transmission BTDF":
//     V_T·D_T at H_T = normalize(V − 2(N·L)N + L)), which is the specular V·D at wi mirrored through
//     the surface plane — the reflection lobe turned over, so a rough film blurs what it lets
//     through and a smooth one (α = 10⁻³) passes it straight; with a volume, an impulse (below);
//   KHR_materials_anisotropy — the specular V·D of both the dielectric and the metal becomes
//     anisotropic GGX: α along the anisotropy direction mix(α, 1, strength²), α across it;
//   KHR_materials_diffuse_transmission — base becomes mix(diffuse_brdf, diffuse_btdf,
//     diffuseTransmission), the BTDF color/π for wi on the other side, weighed by the dielectric's
//     1 − specular·max(fr) with fr at the normal (the pair has no half vector);
//   KHR_materials_iridescence — both Fresnel terms (the dielectric's fr and the metal's Schlick on
//     base_color) become mix(F_schlick, F_thin_film, iridescence) (appearance/thin_film.h), the
//     film in air (outside ior 1);
//   KHR_materials_sheen — the Charlie sheen over everything above (appearance/sheen.h):
//     sheen_brdf + material·min(1 − max(sheenColor)·E(wo), 1 − max(sheenColor)·E(wi));
//   KHR_materials_clearcoat — fresnel_coat: mix(material, coat V·D, clearcoat·Fc) with
//     Fc = 0.04 + 0.96·(1 − |wo·Nc|)^5 on the coat's own normal Nc (the extension's text: the
//     view's cosine to Nc, not wo·h, which keeps the layering energy-conserving; this makes the coat
//     non-reciprocal exactly as the specification defines it), α_c = clearcoatRoughness².
//   KHR_materials_volume — the transmission refracts into or out of the mesh (ShadingParams),
//     its radiance scaled by 1/eta² as it crosses (CGPP §27.5; the factors cancel on a path that
//     enters and leaves a volume); the integrator attenuates what travels inside.
// With the extensions at their defaults (ior 1.5, specular 1, color 1, σ 0, transmission 0, no
// anisotropy, iridescence, sheen or coat) it is gltf_eval exactly. The thin-walled transmission is
//   (1 − clearcoat·Fc)·(1 − metallic)·transmission·(1 − specular·max(fr))·base_color·V·D(wi', wo),
// wi' = (wi.x, wi.y, −wi.z), fr at |wo·H_T|, under the sheen's albedo scaling at (wi', wo), and is
// sampled as the reflection's visible normals, mirrored. The transmission into or out of a volume
// is an impulse refracted about the shading normal, of magnitude
// (1 − metallic)·transmission·(1 − specular·max(fr))·base_color, fr at h = n, under the sheen's
// albedo scaling and the coat's (1 − clearcoat·Fc): a rough surface over a volume refracts as a
// smooth one (a limit: Walter et al. 2007's rough refraction is not modelled).
#include "appearance/bsdf.h"
#include "appearance/shading.h"

namespace svbrdf {

// The material's parameters at one point, textures applied (glTF §3.9: factors multiply textures;
// COLOR_0 multiplies base color).
struct ShadingParams {
  Rgb base_color{1.0f};  // linear
  float metallic = 0.0f;
  float roughness = 1.0f;  // perceptual
  Rgb emission{0.0f};      // radiance, before the coat darkens it (coat_transmittance)
  float ior = 1.5f;
  float specular = 1.0f;
  Rgb specular_color{1.0f};
  float transmission = 0.0f;
  float diffuse_roughness = 0.0f;
  bool unlit = false;
  // KHR_materials_anisotropy: strength in [0, 1] and the unit direction of increased roughness in
  // the shading frame's x–y plane (the texture's direction, rotated by anisotropyRotation).
  float anisotropy = 0.0f;
  glm::vec2 anisotropy_direction{1.0f, 0.0f};
  // KHR_materials_diffuse_transmission: the share of the diffuse base that crosses the surface and
  // leaves on the other side as Lambertian (color/π), and its linear color.
  float diffuse_transmission = 0.0f;
  Rgb diffuse_transmission_color{1.0f};
  // KHR_materials_sheen: the linear sheen color and its perceptual roughness.
  Rgb sheen_color{0.0f};
  float sheen_roughness = 0.0f;
  // KHR_materials_iridescence: the film's weight, ior and thickness (nm).
  float iridescence = 0.0f;
  float iridescence_ior = 1.3f;
  float iridescence_thickness = 400.0f;
  // KHR_materials_volume: a material with a volume refracts its transmission into or out of the
  // mesh (Snell, eta = n(beyond)/n(here), the ratio the integrator's medium stack knows) instead of
  // passing it straight through; leaving a denser medium, the dielectric's Fresnel is Schlick's at
  // the transmitted angle, and 1 past the critical angle (total internal reflection).
  bool thin_walled = true;
  float eta = 1.5f;
  // KHR_materials_clearcoat: the layer's weight, perceptual roughness and unit normal in the
  // shading frame (the surface's normal before the base's normal map, or the coat's own map).
  float clearcoat = 0.0f;
  float clearcoat_roughness = 0.0f;
  glm::vec3 clearcoat_normal{0.0f, 0.0f, 1.0f};
};

// The clear coat's Fresnel weight clearcoat·Fc for a view at cosine `cos_view` to the coat's normal
// (KHR_materials_clearcoat, fresnel_coat with ior 1.5): what the coat reflects of the view, and
// 1 minus what it lets through of everything below it, emission included.
float clearcoat_blend(float clearcoat, float cos_view);

class SurfaceBsdf final : public Bsdf {
 public:
  explicit SurfaceBsdf(const ShadingParams& p);

  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  Impulses impulses_in(const glm::vec3& wo) const override;
  Impulses impulses_out(const glm::vec3& wi) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;

  // Whether the transmission is an impulse: refraction into or out of a volume.
  bool has_impulse() const { return transmission_weight_ > 0.0f && !p_.thin_walled; }
  // Whether eval can be non-zero for wi on the other side of the surface (diffuse transmission, or
  // a thin-walled specular transmission).
  bool transmits_finitely() const { return diffuse_transmits() || thin_transmission_; }

 private:
  struct LobeChoice {
    // probabilities, summing to 1 (or all 0)
    float coat = 0, specular = 0, sheen = 0, diffuse = 0, diffuse_transmission = 0, transmission = 0;
  };
  LobeChoice choose(const glm::vec3& wo) const;
  Rgb transmission_magnitude(const glm::vec3& wo) const;
  // The transmitted direction for the view w (its side: z > 0) and the impulse's magnitude; false
  // when nothing is transmitted (no transmission, or total internal reflection).
  bool transmitted(const glm::vec3& w, glm::vec3& wt, Rgb& magnitude) const;
  Rgb diffuse_f(const glm::vec3& wi, const glm::vec3& wo) const;
  // The diffuse BTDF term for wi below (wi.z < 0) and wo above, all layers applied.
  Rgb diffuse_transmission_f(const glm::vec3& wi, const glm::vec3& wo) const;
  bool diffuse_transmits() const { return p_.diffuse_transmission > 0.0f && p_.metallic < 1.0f; }
  // The thin-walled specular BTDF term for wi below (wi.z < 0) and wo above, all layers applied.
  Rgb specular_transmission_f(const glm::vec3& wi, const glm::vec3& wo) const;
  // A direction mirrored through the surface plane: the thin-walled BTDF's reflected twin.
  static glm::vec3 mirrored(const glm::vec3& w) { return {w.x, w.y, -w.z}; }
  // The base material (everything under the coat) for both directions above the base's horizon.
  Rgb base_f(const glm::vec3& wi, const glm::vec3& wo) const;
  // The coat's V·D (no Fresnel) and the density of its sampler, in the shading frame.
  float coat_vd(const glm::vec3& wi, const glm::vec3& wo) const;
  float coat_pdf(const glm::vec3& wi, const glm::vec3& wo) const;
  // The base's specular V·D and the density of its sampler (isotropic or anisotropic GGX).
  float specular_vd(const glm::vec3& wi, const glm::vec3& wo, const glm::vec3& h) const;
  float specular_pdf(const glm::vec3& wi, const glm::vec3& wo) const;
  glm::vec3 sample_specular_normal(const glm::vec3& wo, const glm::vec2& u) const;
  // Directions in the anisotropy frame (x = the direction of increased roughness) and back.
  glm::vec3 to_anisotropy(const glm::vec3& w) const;
  glm::vec3 from_anisotropy(const glm::vec3& w) const;
  float coat_blend(const glm::vec3& wo) const;
  // The dielectric's and the metal's Fresnel at cosine c = |wo·h| (Schlick weight w), with the film.
  Rgb dielectric_fresnel(float c, float w) const;
  Rgb metal_fresnel(float c, float w) const;
  bool has_sheen() const { return max_channel(p_.sheen_color) > 0.0f; }

  ShadingParams p_;
  float alpha_;
  glm::vec2 alpha_aniso_;  // (along, across) the anisotropy direction; used when anisotropic_
  bool anisotropic_;
  float coat_alpha_;
  glm::vec3 coat_t_, coat_b_;  // a tangent frame around the coat normal (the coat is isotropic)
  Rgb f0_;
  float transmission_weight_;
  bool thin_transmission_;  // a thin-walled specular transmission: finite, in eval
};

}  // namespace svbrdf
