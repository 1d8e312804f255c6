#pragma once
// Cook–Torrance 1982 (CGPP §27.8.1): the alias for `microfacet distribution=beckmann
// masking=vgroove` of brdf-models.md; every other microfacet parameter keeps its meaning.
#include "appearance/microfacet.h"

namespace svbrdf {

inline MicrofacetParams cook_torrance_params(MicrofacetParams p = {}) {
  p.distribution = MicrofacetType::beckmann;
  p.masking = Masking::vgroove;
  return p;
}

}  // namespace svbrdf
