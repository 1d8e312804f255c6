#pragma once
// KHR_materials_sheen: the "Charlie" sheen lobe of Estevez & Kulla 2017, "Production Friendly
// Microfacet Sheen BRDF" (SIGGRAPH 2017 course), as the extension's implementation notes use it,
// and the albedo-scaling layering of the same paper that puts it on top of a base BRDF.
//
// Frame and units: directions are unit vectors in the local shading frame (z = normal), both
// pointing away from the surface (wi toward the light, wo toward the viewer), as in bsdf.h.
// `sheen_roughness` is the glTF sheenRoughness in [0, 1]; `sheen_color` the linear sheenColor.
#include <glm/glm.hpp>

#include "appearance/bsdf.h"

namespace svbrdf {

// The smallest distribution parameter α = sheenRoughness² used. The extension sets none, but the
// paper's fitted Λ (below) underestimates the shadowing of the sharper distributions so much that
// the lobe's albedo exceeds 1 toward grazing view: the largest albedo over cos θo ∈ [1e-4, 1] is
// 1.58 at α = 0.02, 1.20 at 0.04, 1.04 at 0.06 and 0.99 at 0.07 (midpoint quadrature in double,
// near cos θo = 0.004 each time). 0.07 is the smallest of those that keeps the lobe energy
// conserving; sheenRoughness below √0.07 ≈ 0.265 looks the same as 0.265.
inline constexpr float kSheenMinAlpha = 0.07f;

// α = max(sheenRoughness², kSheenMinAlpha): the extension squares the roughness as the base
// material does (sheenRoughness is perceptual).
float sheen_alpha(float sheen_roughness);

// The Charlie distribution of half-vector cosine cos_h = h.z (Estevez & Kulla eq. 2):
//   D(h) = (2 + 1/α) sin(θh)^(1/α) / (2π),  normalized so that ∫ D(h) cos θh dωh = 1.
double sheen_distribution(double cos_h, double alpha);

// The paper's curve fit of the Smith Λ of the Charlie distribution (Estevez & Kulla §3, table 1):
//   L(x) = a / (1 + b x^c) + d x + e, parameters interpolated between the fits at α = 0 and α = 1
//   with weight (1 − α)²; Λ(cos θ) = exp(L(cos θ)) for cos θ < 0.5 and exp(2L(0.5) − L(1 − cos θ))
//   above, which keeps Λ smooth at 0.5 and makes Λ(1) vanish. The paper's non-physical terminator
//   softening (a light-side exponent on Λ) is not applied: the extension's visibility omits it,
//   and it would break reciprocity.
double sheen_lambda(double cos_theta, double alpha);

// sheen_lambda at one α, the fit's constants and its L(0.5) taken once: for callers that take Λ at many
// cosines of one α (a coarse texel's spread normals, mip/sheen_layer.cpp). Equal to sheen_lambda bit
// for bit.
class SheenLambda {
 public:
  explicit SheenLambda(double alpha);
  double operator()(double cos_theta) const;
  // The same expression in float (the renderer's spread sheen; within 1e-5 relative of the double).
  float operator()(float cos_theta) const;

 private:
  double a_, b_, c_, d_, e_;
  double l_half_;  // L(0.5)
  float af_, bf_, cf_, df_, ef_, l_half_f_;
};

// The sheen visibility V = G2 / (4 cos θi cos θo) with the height-correlated Smith
// G2 = 1 / (1 + Λ(ωi) + Λ(ωo)) (the extension's "Charlie" sheen visibility); cosines > 0.
double sheen_visibility(double cos_i, double cos_o, double alpha);
// The same V from the two directions' Λ = sheen_lambda(cos, α), for callers that evaluate many pairs
// over a few directions and take each direction's Λ once (the same expression: equal bit for bit).
double sheen_visibility_of(double lambda_i, double lambda_o, double cos_i, double cos_o);

// f_sheen(wi, wo) = sheenColor · D(h) · V (1/sr; the sheen Fresnel is 1, as the extension allows).
// 0 when either direction is at or below the horizon. Reciprocal.
Rgb sheen_brdf(const glm::vec3& wi, const glm::vec3& wo, const Rgb& sheen_color, float sheen_roughness);

// The directional albedo E(μ, sheenRoughness) = ∫ f_sheen(wi, wo) cos θi dωi for sheenColor = 1 and
// wo.z = μ, looked up bilinearly in a 32 × 32 table computed once, on first use, by quadrature of
// sheen_brdf's formula in double (sheen.cpp says how; interpolation error there too).
float sheen_albedo(float mu, float sheen_roughness);

// The extension's albedo scaling of the base layer (Estevez & Kulla §4, after Kelemen &
// Szirmay-Kalos 2001): f = f_sheen + f_base · s with
//   s = min(1 − max3(sheenColor)·E(wo.z), 1 − max3(sheenColor)·E(wi.z)),
// clamped to [0, 1] (E of the fit exceeds 1 within 0.01° of the horizon). Symmetric in wi, wo.
float sheen_albedo_scaling(const glm::vec3& wi, const glm::vec3& wo, const Rgb& sheen_color, float sheen_roughness);

// The sheen lobe's sampler: wi uniform on the upper hemisphere, pdf 1/(2π), independent of wo.
// Uniform rather than cosine-weighted because f_sheen·cos θi leans toward the horizon: over
// α ∈ {0.07, 0.3, 1} and θo ∈ {0°, 45.6°, 72.5°, 87.1°} the relative variance of f·cos/pdf is
// 0.06–2.6 uniform against 0.26–10.3 cosine-weighted (quadrature in double).
glm::vec3 sample_sheen(const glm::vec2& u);
float sheen_pdf(const glm::vec3& wi, const glm::vec3& wo);

// The sheen lobe alone as a model of the §27.14 interface (registry name "sheen"): eval is
// sheen_brdf, sampling is sample_sheen inside the energy split of bsdf.h with scatter probability
// min(1, max3(sheenColor)·E(wo.z)), the lobe's own albedo.
class Sheen final : public Bsdf {
 public:
  Sheen(const Rgb& sheen_color, float sheen_roughness);
  Rgb eval(const glm::vec3& wi, const glm::vec3& wo) const override;
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override;
  float pdf(const glm::vec3& wi, const glm::vec3& wo) const override;
  float scatter_probability(const glm::vec3& wo) const override;

 private:
  Rgb color_;
  float roughness_;
};

}  // namespace svbrdf
