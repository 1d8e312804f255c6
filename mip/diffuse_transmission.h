#pragma once
// KHR_materials_diffuse_transmission in the BRDF MIP's lobes (lobe.h). The extension's "Implementation"
// (KhronosGroup/glTF, extensions/2.0/Khronos/KHR_materials_diffuse_transmission/README.md) changes the
// dielectric's base to
//   base = mix(diffuse_bsdf, specular_btdf·baseColor, transmission),
//   diffuse_bsdf = mix(diffuse_brdf(baseColor), diffuse_btdf(diffuseTransmissionColor), diffuseTransmission),
// diffuse_btdf(C) = C/π for light and view on opposite sides, under fresnel_mix's 1 − s·max(fr); the
// renderer takes fr at the shading normal, n·wo (appearance/gltf_surface_bsdf.h: the pair has no half
// vector). So a texel of metallic m, transmission T, share d and colour C, with the specular layer's
// s and f0 (lobe.h lobe_from_texel), transmits for wi below and wo above its normal's plane
//   f = (1 − m)·(1 − T)·d·(1 − s·max(f0 + (1 − f0)·w))·C/π = (τd + (τd90 − τd)·w)/π,  w = (1 − n·wo)^5,
//   τd = (1 − m)·(1 − T)·d·(1 − s·max(f0))·C,   τd90 = (1 − m)·(1 − T)·d·(1 − s)·C
// (max over channels of f0 + (1 − f0)·w is max(f0) + (1 − max(f0))·w, as for ρ), and its diffuse
// reflection's ρ and ρ90 take 1 − d. Its f_eff is f·max(0, −n·wi)·[n·wo > 0]/|wi.z|.
//
// τd and τd90 are linear in the texels' parameters as ρ is: a merge averages them by weight and divides
// them by its flux rescaling as it does ρ (lobe_reduction.cpp), so weight·τd is the exact mean
// amplitude, then scales them to keep the union's flux where amplitude and normal correlate
// (diffuse_transmission_flux).
// A lobe transmits, for wi below and wo above the geometric surface,
//   weight·(τd + (τd90 − τd)·w(n̂·wo))/π · E[max(0, −n·wi)]·P(n·wo > 0) / |wi.z|,
// its two sides those of the mirrored pair (wi mirrored through n̂'s plane, as the thin-walled
// transmission's, lobe.h "Transmission"): exactly the texel's f_eff at level 0 (n̂ = n). What a coarse
// lobe does not carry: w at the mean normal rather than the mean of w over the normals' spread (the
// Schlick weight's curvature, small but for grazing views), and the product of the mean amplitude and
// the mean clipped cosine where amplitude and normal correlate (the diffuse reflection's E[ρ·n]).
// Under a sheen and a coat it is layered as the transmission is: the sheen's albedo scaling at the
// mirrored pair and the coat's 1 − c·Fc(wo) (exact_reference.cpp, lobe_mixture_bsdf.cpp).
#include <algorithm>

#include <glm/glm.hpp>

#include "mip/lobe.h"
#include "textures/material_texels.h"

namespace svbrdf {

// Whether a lobe transmits diffusely.
inline bool diffuse_transmits(const Lobe& l) {
  const glm::vec3 s = l.diffuse_transmission + l.diffuse_transmission90;
  return s.r > 0.0f || s.g > 0.0f || s.b > 0.0f;
}

// Gives the level-0 lobe of a texel (lobe_from_texel with the same metallic, layer and transmission) the
// texel's diffuse transmission: τd, τd90 above, and ρ, ρ90 times 1 − d. A share of 0 leaves it as it was.
inline void add_diffuse_transmission(Lobe& l, float metallic, const SpecularLayer& layer, float transmission,
                                     const DiffuseTransmissionLayer& dt) {
  const float d = std::clamp(dt.share, 0.0f, 1.0f);
  if (!(d > 0.0f)) return;
  const float k = (1.0f - metallic) * (1.0f - std::clamp(transmission, 0.0f, 1.0f)) * d;
  float k0 = 0.96f, k90 = 0.0f;  // 1 − s·max(f0) and 1 − s; the plain layer's 0.96 and 0
  if (!layer.plain()) {
    const glm::vec3 f0 = glm::min(dielectric_f0(layer.ior) * layer.color, glm::vec3(1.0f));
    k0 = 1.0f - layer.specular * std::max(f0.r, std::max(f0.g, f0.b));
    k90 = 1.0f - layer.specular;
  }
  l.diffuse_transmission = (k * k0) * dt.color;
  l.diffuse_transmission90 = (k * k90) * dt.color;
  l.diffuse *= 1.0f - d;
  l.diffuse90 *= 1.0f - d;
}

// The flux a lobe transmits diffusely, per channel, from a uniform far hemisphere at w = 0:
// weight·τd·(1 + n̄_z)/2, n̄ its unnormalized mean normal. One texel's BTDF τd/π over the far hemisphere
// gives τd/π·∫_{wi.z < 0} max(0, −n·wi) dwi = τd·(1 + n_z)/2 (the irradiance of a plane tilted by θ
// from a uniform hemisphere, π·(1 + cos θ)/2), linear in its normal, so a lobe standing for texels of
// one τd transmits their mean. Where τd and the normals correlate, the mean of the products is not the
// product of the means: a merge scales its τd to keep its members' sum (lobe_reduction.cpp).
inline glm::dvec3 diffuse_transmission_flux(const Lobe& l) {
  return double(l.weight) * glm::dvec3(l.diffuse_transmission) * ((1.0 + double(l.normal.z)) / 2.0);
}

// weight · f_eff of a lobe's diffuse transmission (the top of this file) for wi below and wo above the
// geometric surface, 0 elsewhere; `sides`, when given, receives the product of its two sides' factors
// (those of the mirrored pair: lobe_transmission_eval's for the same lobe and directions).
template <class T>
glm::vec<3, T> lobe_diffuse_transmission_eval(const Lobe& lobe, const LobeShape<T>& s, const glm::vec<3, T>& wi,
                                              const glm::vec<3, T>& wo, T* sides = nullptr) {
  using V3 = glm::vec<3, T>;
  if (sides) *sides = 0;
  if (!s.valid || !diffuse_transmits(lobe) || !(wi.z < 0) || !(wo.z > 0)) return V3(0);
  const LobeSide<T> i = lobe_wi_side(s, -glm::dot(s.n, wi));
  if (!(i.factor > 0)) return V3(0);
  const LobeSide<T> o = lobe_wo_side(s, glm::dot(s.n, wo));
  if (!(o.factor > 0)) return V3(0);
  if (sides) *sides = i.factor * o.factor;
  const T w = schlick_weight(std::min(o.c, T(1)));
  const V3 t(lobe.diffuse_transmission), t90(lobe.diffuse_transmission90);
  return (T(lobe.weight) * i.factor * o.factor * kInvPiOf<T> / -wi.z) * (t + (t90 - t) * w);
}

}  // namespace svbrdf
