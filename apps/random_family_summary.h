#pragma once
// The random family's figures over seeds (random_family_measure.h): per level and metric, for `brdf`
// and `param`, the median, the 90th percentile and the maximum over seeds, the seed that is worst, and
// how many seeds meet the target of docs/mip-algorithm.md §8 ("The random family"), over all seeds
// and over those outside the glint regime. As a table, with
// a line per seed (what it drew, and where it misses a target), or as JSON with every seed's figures.
#include <cstdint>
#include <string>
#include <vector>

#include "apps/random_family_measure.h"
#include "base/json.h"

namespace svbrdf {

// A figure of a level reported over seeds.
struct FamilyMetric {
  const char* name;
  double target;  // the bar a seed's figure must not exceed; NaN: reported, no target
  double (*get)(const ModeFigures&);  // NaN where the seed has no such texels
};
// e_log, e_mean, e_rel mean outside and inside the glint regime, e_rel max, and the directional
// albedo's level total and mean per-texel error (each the largest over θi 0°, 45°, 75°).
const std::vector<FamilyMetric>& family_metrics();

struct Distribution {
  int count = 0;  // seeds with a figure
  double median = 0, p90 = 0, max = 0;
  std::uint64_t worst_seed = 0;
  int meeting = 0;  // seeds whose figure meets the target (0 without one)
};
// A seed is in the glint regime at a level when at least half of the texels measured there are
// (random_family_measure.h): its level means and albedo are then the sum of a few spikes that no
// compact texel follows, so the report gives the distribution over the other seeds beside all.
bool seed_in_glint_regime(const LevelFigures& level);

// Over the seeds' figures at `level` (seeds without that level, or in the glint regime there when
// `without_glints`, are left out); p90 interpolates linearly between order statistics.
Distribution distribution(const std::vector<SeedFigures>& seeds, int level, const FamilyMetric& metric, bool brdf,
                          bool without_glints = false);

// The transmission's figures (random_family_measure.h, transmission_figures.h), reported over the seeds
// that transmit: e_log and |flux − 1| of the transmitted radiance, and of the reflected radiance on the
// same pairs beside them, and the largest |transmittance| over θ (the level's directional transmittance
// against the exact's). No target: docs/mip-algorithm.md §4.6 holds the transmission to the reflection.
struct TransmissionMetric {
  const char* name;
  double (*get)(const TransmissionFigures&);  // NaN where the level has no such figure
};
const std::vector<TransmissionMetric>& transmission_metrics();
Distribution distribution(const std::vector<SeedFigures>& seeds, int level, const TransmissionMetric& metric);

std::string family_table(const std::vector<SeedFigures>& seeds, int size);
Json family_json(const std::vector<SeedFigures>& seeds, int size);

}  // namespace svbrdf
