#include "apps/compare_report.h"

#include <cstdio>

namespace svbrdf {

namespace {
template <class... A>
std::string format(const char* f, A... a) {
  char buf[256];
  std::snprintf(buf, sizeof buf, f, a...);
  return buf;
}
std::string json_string(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\', o += c;
    else if (static_cast<unsigned char>(c) < 0x20) o += format("\\u%04x", c);
    else o += c;
  }
  return o + "\"";
}
}  // namespace

std::string comparison_table(const std::vector<LevelComparison>& levels, int subset) {
  std::string s = format("%-5s %-11s %-15s %-8s %10s %10s %10s %10s %8s\n", "level", "size", "texels", "mode",
                         "e_rel_mean", "e_rel_max", "e_log", "e_mean", "bytes/tx");
  for (const LevelComparison& l : levels)
    for (const ModeLevelStats& m : l.modes) {
      const std::string size = std::to_string(l.extent.width) + "x" + std::to_string(l.extent.height);
      const std::string texels = l.subset ? std::to_string(l.measured) + " random" : "all " + std::to_string(l.measured);
      const std::string_view mode = mode_name(m.mode);
      s += format("%-5d %-11s %-15s %-8.*s %10.4f %10.4f %10.4f %10.4f %8d\n", l.level, size.c_str(), texels.c_str(),
                  int(mode.size()), mode.data(), m.erel_mean, m.erel_max, m.elog_mean, m.emean, m.bytes_per_texel);
    }
  s += format("e_rel, e_log: ../shared/spec/brdf-mip.md, over the 4225 direction pairs; levels with more than %d texels "
              "are measured on that many texels drawn at random (fixed seed); e_mean over every texel.\n",
              subset);
  return s;
}

std::string comparison_json(const std::vector<LevelComparison>& levels, int subset, const std::string& file) {
  std::string s = "{\"file\": " + json_string(file) + ", \"subset\": " + std::to_string(subset) + ", \"levels\": [";
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const LevelComparison& l = levels[i];
    s += i ? ", " : "";
    s += format("{\"level\": %d, \"width\": %d, \"height\": %d, \"measured\": %d, \"random_subset\": %s, \"modes\": {", l.level,
                l.extent.width, l.extent.height, l.measured, l.subset ? "true" : "false");
    for (std::size_t k = 0; k < l.modes.size(); ++k) {
      const ModeLevelStats& m = l.modes[k];
      const std::string_view mode = mode_name(m.mode);
      s += k ? ", " : "";
      s += format("\"%.*s\": {\"e_rel_mean\": %.6g, \"e_rel_max\": %.6g, \"e_log\": %.6g, \"e_mean\": %.6g, \"bytes_per_texel\": %d}",
                  int(mode.size()), mode.data(), m.erel_mean, m.erel_max, m.elog_mean, m.emean, m.bytes_per_texel);
    }
    s += "}}";
  }
  return s + "]}\n";
}

}  // namespace svbrdf
