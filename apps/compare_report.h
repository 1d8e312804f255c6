#pragma once
// The text `svbrdf-bake compare` prints: a table, one row per level and mode, or the same as JSON.
// Numbers: e_rel mean and max, e_log mean, e_mean with 4 decimals (%.4f) in the table; in the JSON
// (indented, one member a line) six significant digits (%.6g), null for a NaN.
#include <string>
#include <vector>

#include "mip/metrics.h"

namespace svbrdf {

std::string comparison_table(const std::vector<LevelComparison>& levels, int subset);
std::string comparison_json(const std::vector<LevelComparison>& levels, int subset, const std::string& file);

}  // namespace svbrdf
