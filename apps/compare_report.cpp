#include "apps/compare_report.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "base/json.h"

namespace svbrdf {

namespace {
template <class... A>
std::string format(const char* f, A... a) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a...);
  return buf;
}
// Six significant digits (%.6g), what the metrics are good for; a NaN (a metric of nothing) is null,
// which JSON can hold.
Json six_digits(double v) {
  if (!std::isfinite(v)) return nullptr;
  return std::strtod(format("%.6g", v).c_str(), nullptr);
}
}  // namespace

std::string comparison_table(const std::vector<LevelComparison>& levels, int subset) {
  std::string s = format("%-5s %-11s %-15s %-8s %10s %10s %10s %10s %8s\n", "level", "size", "texels", "mode",
                         "e_rel_mean", "e_rel_max", "e_log", "e_mean", "bytes/tx");
  for (const LevelComparison& l : levels)
    for (const ModeLevelStats& m : l.modes) {
      const std::string size = std::to_string(l.extent.width) + "x" + std::to_string(l.extent.height);
      const std::string texels = l.subset ? std::to_string(l.measured) + " random" : "all " + std::to_string(l.measured);
      const std::string_view mode = filter_name(m.mode);
      s += format("%-5d %-11s %-15s %-8.*s %10.4f %10.4f %10.4f %10.4f %8d\n", l.level, size.c_str(), texels.c_str(),
                  int(mode.size()), mode.data(), m.erel_mean, m.erel_max, m.elog_mean, m.emean, m.bytes_per_texel);
    }
  s += format("e_rel, e_log: ../shared/spec/brdf-mip.md, over the 4225 direction pairs; levels with more than %d texels "
              "are measured on that many texels drawn at random (fixed seed); e_mean over every texel.\n",
              subset);
  return s;
}

std::string comparison_json(const std::vector<LevelComparison>& levels, int subset, const std::string& file) {
  Json rows = Json::array();
  for (const LevelComparison& l : levels) {
    Json modes = Json::object();
    for (const ModeLevelStats& m : l.modes) {
      Json stats = {{"e_rel_mean", six_digits(m.erel_mean)},
                    {"e_rel_max", six_digits(m.erel_max)},
                    {"e_log", six_digits(m.elog_mean)},
                    {"e_mean", six_digits(m.emean)},
                    {"bytes_per_texel", m.bytes_per_texel}};
      modes[std::string(filter_name(m.mode))] = std::move(stats);
    }
    rows.push_back({{"level", l.level},
                    {"width", l.extent.width},
                    {"height", l.extent.height},
                    {"measured", l.measured},
                    {"random_subset", l.subset},
                    {"modes", std::move(modes)}});
  }
  return json_text({{"file", file}, {"subset", subset}, {"levels", std::move(rows)}});
}

}  // namespace svbrdf
