#pragma once
// Everything a MIP file holds for one material: the level-0 parameters (so `exact` can be computed),
// the parameter pyramid (`param` and the engine baselines) and the BRDF pyramid (`brdf`), and the
// ways ../shared/spec/brdf-mip.md names to answer for a texel (svbrdf-bake eval and compare).
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "mip/brdf_pyramid.h"
#include "mip/direction_grid.h"
#include "mip/exact_reference.h"
#include "mip/param_pyramid.h"
#include "mip/texture_filter.h"
#include "textures/material_texels.h"

namespace svbrdf {

struct MipData {
  MaterialTexels level0;
  ParamPyramid param;
  BrdfPyramid brdf;

  int levels() const { return param.levels(); }
  Extent extent(int level) const { return param.extent(level); }
};

// The BRDF pyramid's lobes of texel (i, j) of `level`: a view into the pyramid for levels ≥ 1, valid
// while it lives; at level 0, which the pyramid does not hold (its lobes are the texels'), the
// texel's one lobe, made into `scratch`.
inline std::span<const Lobe> brdf_texel(const MipData& mip, int level, int i, int j, Lobe& scratch) {
  if (level >= 1) return mip.brdf.texel(level, i, j);
  scratch = level0_lobe(mip.level0, mip.level0.index(i, j));
  return {&scratch, 1};
}

// The same texel's coat (coat_layer.h): the pyramid's for levels ≥ 1, at level 0 the texel's own
// coat lobe made into `scratch`; none for a material without a coat.
inline CoatTexel brdf_coat(const MipData& mip, int level, int i, int j, Lobe& scratch) {
  if (level >= 1) return mip.brdf.coat(level, i, j);
  return level0_coat(mip.level0, mip.level0.index(i, j), scratch);
}

// The same texel's sheen means (sheen_layer.h): the pyramid's for levels ≥ 1, at level 0 the texel's
// own; null for a material without a sheen.
inline const SheenLayer* brdf_sheen(const MipData& mip, int level, int i, int j) {
  if (!mip.brdf.has_sheen()) return nullptr;
  if (level >= 1) return &mip.brdf.sheen(level, i, j);
  return mip.param.sheen(0, i, j);
}

// Builds both pyramids over `level0` (moved in); `brdf_seconds`, when given, receives the BRDF
// pyramid's share of the time (the figure bench/results/mip.md sets against maketx).
MipData build_mip(MaterialTexels level0, const BrdfBuildOptions& options = {},
                  std::vector<BrdfLevelStats>* stats = nullptr, double* brdf_seconds = nullptr);

// Throws svbrdf::Error (bad input) naming the level or texel when it is out of range.
void check_texel(const MipData& mip, int level, int i, int j);

// The spec's ways to answer for a coarse texel are the reference `exact` (ExactReference over
// mip.level0, exact_reference.h) and the filters that store texels: param, toksvig, vmf (the
// parameter pyramid under the filter's α widening) and brdf (the BRDF pyramid). The functions below
// answer for the filters; `filter` must not be level0, which stores no coarse texel.

// F of texel (i, j) of `level` under a filter, directions in the geometric tangent frame, its lobes
// evaluated in float as the renderer evaluates them.
glm::dvec3 texel_eval(const MipData& mip, TextureFilter filter, int level, int i, int j, const glm::dvec3& wi,
                      const glm::dvec3& wo);
// The same over the metric's 4225 pairs.
BrdfTable texel_table(const MipData& mip, TextureFilter filter, int level, int i, int j);

// acc += weight · the BRDF pyramid's texel (level, i, j) over the direction grid's pairs, in float as
// the renderer evaluates it, with its radial correction (radial_correction.h), its lobes under a tint
// of the base color (lobe.h tinted; a pyramid built tintable, unless the tint is 1) and its coat
// (coat_layer.h).
void accumulate_brdf_texel(const MipData& mip, int level, int i, int j, double weight, std::span<glm::dvec3> acc,
                           const glm::vec3& tint = glm::vec3(1.0f));

// acc += weight · the parameter filters' texel (level, i, j) under `filter` (param, toksvig, vmf) over
// the direction grid's pairs, in float as the renderer evaluates it: the lobe of its mean parameters and
// specular layer under its mean coat (param_pyramid.h param_lobes).
void accumulate_param_texel(const MipData& mip, TextureFilter filter, int level, int i, int j, double weight,
                            std::span<glm::dvec3> acc);

// Bytes per texel a filter stores at a level.
int bytes_per_texel(const MipData& mip, TextureFilter filter, int level);

}  // namespace svbrdf
