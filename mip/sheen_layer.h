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
// under its coat. This is the sheen of the exact reference's level-0 texels; the BRDF pyramid holds
// none, and a material with one stays out of it (gltf_material.h mip_unsupported).
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

}  // namespace svbrdf
