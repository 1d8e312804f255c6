#pragma once
// One seed of the random material family (textures/random_material.h) through the BRDF pyramid: per
// level ≥ 1, the metrics of ../shared/spec/brdf-mip.md against the exact reference (through
// compare_levels, the code of `svbrdf-bake compare`) and the directional albedo, for `param` and
// `brdf`. What `svbrdf-bake random-family` reports over seeds (random_family_summary.h) and what the
// random-family tests assert.
//
// The glint regime (the spec's "Glints"): a coarse texel is in it when at least two of the level-0
// texels it covers are glossy (perceptual roughness < kGlintRoughness, the spec's "below ~0.3") and
// the glossy texels' normals spread about their mean direction by an RMS angle at least their RMS α
// (in radians, about a GGX lobe's angular half-width): their highlights are then separate spikes
// rather than one widened lobe, however few glossy texels there are (one α = 0.001 texel outshines
// fifteen α = 0.03 ones at their peaks 50 times over). e_rel's mean is reported over the measured
// texels in the regime and over the others, since the spec expects no compact texel to follow the
// former.
//
// The directional albedo ∫ F·wo.z dωo at θi = 0°, 45°, 75° (azimuth 0), the mean of the three
// channels, by directional_albedo (mip/metrics.h, 16² strata per technique) of a texel's lobes —
// without the radial correction, as the preset tests measure it; exact is the covered level-0 texels'
// mean of the same quadrature (the albedo is linear in the texels). Per level: the relative error of
// the level's total (area-weighted), and the texels' mean absolute error relative to the level's mean
// albedo (a texel turned away from a grazing light reflects nothing, so its own relative error is
// not defined).
//
// A seed that transmits (KHR_materials_transmission) also gets, per level, the transmitted radiance's
// e_log and flux beside the reflected radiance's, measured on the same pairs (transmission_figures.h);
// the albedo above is the reflected light's.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "apps/transmission_figures.h"
#include "mip/metrics.h"
#include "textures/random_material.h"

namespace svbrdf {

inline constexpr float kGlintRoughness = 0.3f;

// Whether texel (i, j) of `level` is in the glint regime (above).
bool in_glint_regime(const MaterialTexels& level0, int level, int i, int j);

struct ModeFigures {
  double elog_mean = 0, emean = 0, erel_mean = 0, erel_max = 0;
  double erel_mean_glint = 0, erel_mean_other = 0;  // NaN where no measured texel is of that kind
  std::array<double, 3> albedo_total{};             // level total / exact − 1, per θi
  std::array<double, 3> albedo_texel{};             // Σ |texel − exact| / Σ exact (area-weighted), per θi
};

struct LevelFigures {
  int level = 0;
  int measured = 0;  // texels whose e_rel / e_log were measured (compare_levels' subset)
  int glint = 0;     // of them, in the glint regime
  ModeFigures param, brdf;
  // A seed that transmits: `brdf`'s transmission beside its reflection (transmission_figures.h).
  bool transmits = false;
  TransmissionFigures transmission;
};

struct SeedFigures {
  std::uint64_t seed = 0;
  std::string summary;  // what the seed drew (RandomMaterialDraw::summary)
  std::vector<LevelFigures> levels;  // levels 1 .. last
};

// Builds seed's texture at size² and its pyramids (default options but `build`) and measures them.
SeedFigures measure_random_seed(std::uint64_t seed, int size, const BrdfBuildOptions& build = {});
// The same of a draw (a seed's, or one with an ingredient taken out).
SeedFigures measure_random_draw(const RandomMaterialDraw& draw, int size, const BrdfBuildOptions& build = {});

}  // namespace svbrdf
