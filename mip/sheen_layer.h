#pragma once
// The sheen of KHR_materials_sheen at a level-0 texel, in the terms of the BRDF MIP's effective BRDF
// f_eff (../shared/spec/brdf-mip.md). The extension puts the Charlie sheen of appearance/sheen.h on top
// of the material below it by albedo scaling (the glTF surface BSDF's base_f), in the frame of the
// texel's shading normal n:
//   f = f_sheen + s·f_material,  f_sheen = C·D(n·h)·V(n·wi, n·wo),
//   s = clamp(min(1 − max(C)·E(n·wo), 1 − max(C)·E(n·wi)), 0, 1),
// C the sheen colour, D and V the Charlie distribution and visibility at α = sheen_alpha(roughness), E
// the sheen lobe's directional albedo (sheen_albedo). The clear coat, where there is one, lies over
// both (coat_layer.h: f is its f_base). f_eff multiplies f by max(0, n·wi)/wi.z and vanishes where
// n·wo ≤ 0, so a texel with a sheen reflects
//   f_eff = s·f_eff,material + f_sheen·max(0, n·wi)·[n·wo > 0]/wi.z
// under its coat (sheen_terms below: the exact reference's level-0 texels).
//
// A coarse texel's mean of that is not a lobe of lobe.h: the sheen is neither linear in the texel's
// parameters nor a function of the pair alone. It keeps the shape of the coat layer (coat_layer.h):
//   the texel's sheen — its texels' mean colour C̄ and mean perceptual roughness r̄ (a SheenLayer, the
//     parameter pyramid's sheen means at the same level, sheen_from_below), and
//   each base lobe's sheen share σ_k = the mean of max(C) over the texels it stands for (Lobe::sheen),
//     averaged by merges as F0 is.
// Base lobe k is scaled by its texels' albedo scaling about its own mean normal n̂_k,
//   s_k = clamp(min(1 − σ_k·E(n̂_k·wo, r̄), 1 − σ_k·E(n̂_k·wi, r̄)), 0, 1),
// and the sheen itself is the base lobes' normals (the extension's sheen lies on the base's shading
// normal, which the base lobes already stand for, with their spread and horizons) weighted by their
// sheen shares:
//   f_sheen,eff = C̄ · Σ_k w_k·σ_k·E_k[D(n·h, r̄)·V(n·wi, n·wo, r̄)·max(0, n·wi)·[n·wo > 0]]
//                     / (Σ_k w_k·σ_k · wi.z),
// E_k the mean over lobe k's normals n, spread about n̂_k as its horizons assume (lobe.h; the term at
// n̂_k for a lobe without spread; sheen_layer.cpp, spread_sheen, says how and why). At level 0 (one
// texel, one lobe of weight 1, σ = max(C), C̄ = C, r̄ = r) both are f_eff above exactly. Why this form:
// s_x is linear in max(C_x) for one E, so a base lobe's own mean max(C) carries the correlation of the
// sheen with the base it scales, as a lobe's coat share does (a texel-wide s would scale a rough sheen-
// less part by a glossy part's sheen); the sheen's normals are the base's, so separate sheen lobes
// would store a second copy of them. What it does not carry: a sheen colour or roughness that varies
// within the texel other than through σ_k (C̄ and r̄ are one per texel), the curvature of D and E in the
// roughness, and normals whose spread is not the horizons' Gaussian. At K base lobes the MIP file stores
// 2·K bytes (σ_k as a half) beside the parameter pyramid's 16 bytes of sheen means (mip_file.h).
#include <algorithm>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "mip/lobe.h"
#include "textures/material_texels.h"

namespace svbrdf {

// What the sheen of one texel does to a direction pair: its own term f_sheen·max(0, n·wi)/wi.z (zero
// where n faces away from either direction) and the scaling s of the material below it.
struct SheenTerms {
  glm::dvec3 f{0.0};
  double scaling = 1.0;
};

// The sheen terms of a texel with sheen `sheen` about its unit shading normal n, in double precision
// (E, a table of floats, at the cosines rounded to float): the exact reference's.
SheenTerms sheen_terms(const SheenLayer& sheen, const glm::dvec3& n, const PairTerms<double>& p);

// f ← s·f + f_sheen (sheen_terms) at every pair of the direction grid, f the table of the material
// below the sheen (direction_grid.h). Equal to sheen_terms pair by pair, bit for bit; each direction's
// cosine, Λ and E are taken once rather than once a pair (the exact reference spends most of a sheen
// texel's time on them otherwise).
void apply_sheen(const SheenLayer& sheen, const glm::dvec3& n, std::span<glm::dvec3> f);

// A texel's sheen share: max(C) of its colour, clamped to [0, 1] as the scaling is (Lobe::sheen).
inline float sheen_share(const SheenLayer& s) { return std::clamp(std::max(s.color.r, std::max(s.color.g, s.color.b)), 0.0f, 1.0f); }

// The sheen means of level 0: every texel's own sheen (the coarser levels': param_pyramid.h
// sheen_from_below, which the parameter pyramid stores and the BRDF pyramid reads).
std::vector<SheenLayer> sheen_level0(const MaterialTexels& m);

// What a texel's sheen does to one of its base lobes for a pair: the scaling s_k of the lobe's terms
// and the lobe's part of the sheen term (the top of this file) before C̄/Σ_j w_j·σ_j.
struct SheenLobeTerms {
  float scaling = 1.0f;
  float sheen = 0.0f;  // w_k·σ_k·D·V·(the lobe's two sides' factors)/wi.z
};

// The same for lobe `l` of shape `s`, given the product of its two sides' factors (lobe_eval's `sides`),
// in float (the renderer's; D and V in double as appearance/sheen.h computes them).
SheenLobeTerms sheen_lobe_terms(const Lobe& l, const LobeShape<float>& s, const PairTerms<float>& p, float sides,
                                float roughness);

}  // namespace svbrdf
