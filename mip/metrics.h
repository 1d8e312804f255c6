#pragma once
// The error metrics of ../shared/spec/brdf-mip.md ("The error metric") and the per-level comparison
// that `svbrdf-bake compare` prints.
//
// For a texel, with L = F·wi.z over the 4225 pairs of direction_grid.h and the three channels:
//   e_rel = sqrt(Σ (L̂ − L)²) / sqrt(Σ L²),
//   e_log = sqrt(mean of (log(1 + L̂) − log(1 + L))²).
// A level reports the mean and max of e_rel and the mean of e_log over its texels, or over a random
// subset of `subset` texels (default 256, drawn without replacement with a fixed seed) when it has
// more than that; and e_mean, the e_rel of the level's mean F against the texture's mean F (the
// exact level mean, the same at every level). Means over a level weigh texels by the level-0 texels
// they cover (all equal for power-of-two sizes).
//
// Cost: the exact tables of the first level with at most `subset` texels are computed from level 0
// (every level-0 texel once: the texture mean needs that anyway); the coarser levels' exact tables are
// the covered-count-weighted means of their children's; finer levels evaluate their subset directly.
#include <cstdint>
#include <vector>

#include "mip/direction_grid.h"
#include "mip/mip_data.h"

namespace svbrdf {

double e_rel(const BrdfTable& approx, const BrdfTable& exact);
double e_log(const BrdfTable& approx, const BrdfTable& exact);

// One mode's figures at a level: the spec's word for a way to answer for a coarse texel; here a
// filter that stores texels (param, toksvig, vmf, brdf), measured against `exact`.
struct ModeLevelStats {
  TextureFilter mode = TextureFilter::param;
  double erel_mean = 0, erel_max = 0, elog_mean = 0, emean = 0;
  int bytes_per_texel = 0;
};

struct LevelComparison {
  int level = 0;
  Extent extent{};
  int measured = 0;     // texels whose e_rel / e_log were measured
  bool subset = false;  // a random subset of the level
  std::vector<ModeLevelStats> modes;
};

struct CompareOptions {
  int first_level = 1;
  int last_level = -1;  // -1: the last level
  int subset = 256;
  std::uint64_t seed = 1;
  std::vector<TextureFilter> modes{TextureFilter::param, TextureFilter::toksvig, TextureFilter::vmf,
                                   TextureFilter::brdf};
};

// Throws svbrdf::Error (bad input) when the level range is outside the pyramid or a mode is level0.
std::vector<LevelComparison> compare_levels(const MipData& mip, const CompareOptions& options);

// The texels a level measures: all of them, or `subset` of them at random (fixed seed), sorted.
std::vector<int> measured_texels(Extent extent, int subset, std::uint64_t seed, int level);

// ∫ f(wi, wo)·wo.z dwo of a set of lobes (the reflected flux per unit incident flux), by
// multiple-importance quadrature per lobe (cosine and the lobe's GGX half vectors, stratified).
glm::dvec3 directional_albedo(std::span<const Lobe> lobes, const glm::dvec3& wi, int strata = 32);
// The same of a coated texel (coat_layer.h): its base lobes under the coat's attenuation, and its coat
// lobes, each sampled by its own shape.
glm::dvec3 directional_albedo(std::span<const Lobe> base, const CoatTexel& coat, const glm::dvec3& wi, int strata = 32);
// The same of a texel with a sheen (sheen_layer.h) and no coat: each base lobe under its albedo scaling
// with its part of the sheen, evaluated in float as the renderer evaluates it, each sampled by its own
// shape (whose cosine share covers the sheen's hemisphere). At level 0 (a texel's own lobe and sheen) it
// is the texel's albedo to float precision.
glm::dvec3 directional_albedo(std::span<const Lobe> base, const SheenLayer& sheen, const glm::dvec3& wi, int strata = 32);

}  // namespace svbrdf
