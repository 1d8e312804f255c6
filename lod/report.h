#pragma once
// The LOD report: DIR/index.html and DIR/img/*.png from a comparison's results. Self-contained (no
// network, no script): for each scene (case × view × light) a strip of images per distance —
// every filter, the ground truth, and a false-color error image per filter — charts of relative MSE,
// flux bias and peak ratio against distance as inline SVG, and a table of the numbers; a summary
// table on top. Every file is written atomically, index.html last.
#include <filesystem>
#include <string>

#include "lod/comparison.h"
#include "textures/color.h"

namespace svbrdf {

struct LodReportInfo {
  std::string title = "svbrdf — BRDF-averaged MIP maps at a distance";
  std::string size_name;  // "default" or "full"
  std::string command;    // how it was made, shown in the report
};

// Returns the path of index.html.
std::filesystem::path write_lod_report(const LodResults& results, const LodManifest& manifest,
                                       const std::filesystem::path& dir, const LodReportInfo& info,
                                       const ColorConfig& color = ColorConfig::builtin());

// Inline SVG of a chart with a log₂ x axis (the distances) and a log₁₀ or linear y axis. Exposed for
// the tests (well-formed XML, points inside the plot).
struct ChartSeries {
  std::string name, color;
  bool dashed = false;
  std::vector<double> x, y;  // y ≤ 0 is skipped on a log axis
};
std::string svg_chart(const std::string& title, const std::string& y_label, const std::vector<ChartSeries>& series,
                      bool log_y, int width = 320, int height = 234);


}  // namespace svbrdf
