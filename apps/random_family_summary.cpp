#include "apps/random_family_summary.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include "base/json.h"

namespace svbrdf {

namespace {

// printf into a string of the length it needs (a seed's line of misses has no bound).
template <class... A>
std::string format(const char* f, A... a) {
  std::string s(static_cast<std::size_t>(std::snprintf(nullptr, 0, f, a...)), '\0');
  std::snprintf(s.data(), s.size() + 1, f, a...);
  return s;
}

double largest_abs(const std::array<double, 3>& v) {
  return std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2])});
}

constexpr double kNoTarget = std::numeric_limits<double>::quiet_NaN();

const LevelFigures* find_level(const SeedFigures& s, int level) {
  for (const LevelFigures& l : s.levels)
    if (l.level == level) return &l;
  return nullptr;
}

int last_level(const std::vector<SeedFigures>& seeds) {
  int last = 0;
  for (const SeedFigures& s : seeds)
    if (!s.levels.empty()) last = std::max(last, s.levels.back().level);
  return last;
}

// Six significant digits, what the figures are good for; a NaN (a figure of no texels) is null.
Json six_digits(double v) {
  if (!std::isfinite(v)) return nullptr;
  return std::strtod(format("%.6g", v).c_str(), nullptr);
}

Json mode_json(const ModeFigures& m) {
  Json albedo_total = Json::array(), albedo_texel = Json::array();
  for (std::size_t a = 0; a < 3; ++a) {
    albedo_total.push_back(six_digits(m.albedo_total[a]));
    albedo_texel.push_back(six_digits(m.albedo_texel[a]));
  }
  return {{"e_log", six_digits(m.elog_mean)},
          {"e_mean", six_digits(m.emean)},
          {"e_rel_mean", six_digits(m.erel_mean)},
          {"e_rel_max", six_digits(m.erel_max)},
          {"e_rel_mean_glint", six_digits(m.erel_mean_glint)},
          {"e_rel_mean_other", six_digits(m.erel_mean_other)},
          {"albedo_total", std::move(albedo_total)},
          {"albedo_texel", std::move(albedo_texel)}};
}

}  // namespace

const std::vector<FamilyMetric>& family_metrics() {
  static const std::vector<FamilyMetric> metrics{
      {"e_log", 0.01, [](const ModeFigures& m) { return m.elog_mean; }},
      {"e_mean", 0.005, [](const ModeFigures& m) { return m.emean; }},
      {"e_rel mean, no glints", 0.02, [](const ModeFigures& m) { return m.erel_mean_other; }},
      {"e_rel mean, glints", kNoTarget, [](const ModeFigures& m) { return m.erel_mean_glint; }},
      {"e_rel max", kNoTarget, [](const ModeFigures& m) { return m.erel_max; }},
      {"albedo, level total", 0.005, [](const ModeFigures& m) { return largest_abs(m.albedo_total); }},
      {"albedo, mean per texel", 0.005, [](const ModeFigures& m) { return largest_abs(m.albedo_texel); }},
  };
  return metrics;
}

bool seed_in_glint_regime(const LevelFigures& level) { return 2 * level.glint >= level.measured; }

namespace {

// The distribution of `value(level figures)` over the seeds that have `level` and pass `keep`.
template <class Value, class Keep>
Distribution distribution_of(const std::vector<SeedFigures>& seeds, int level, double target, Value value, Keep keep) {
  std::vector<double> values;
  Distribution d;
  for (const SeedFigures& s : seeds) {
    const LevelFigures* l = find_level(s, level);
    if (!l || !keep(*l)) continue;
    const double v = value(*l);
    if (!std::isfinite(v)) continue;
    values.push_back(v);
    if (values.size() == 1 || v > d.max) d.max = v, d.worst_seed = s.seed;
    if (v <= target) ++d.meeting;  // never for a figure without a target (NaN)
  }
  d.count = static_cast<int>(values.size());
  if (values.empty()) return d;
  std::sort(values.begin(), values.end());
  const auto quantile = [&](double p) {
    const double x = p * double(values.size() - 1);
    const auto k = static_cast<std::size_t>(x);
    return k + 1 < values.size() ? values[k] + (x - double(k)) * (values[k + 1] - values[k]) : values[k];
  };
  d.median = quantile(0.5);
  d.p90 = quantile(0.9);
  return d;
}

}  // namespace

Distribution distribution(const std::vector<SeedFigures>& seeds, int level, const FamilyMetric& metric, bool brdf,
                          bool without_glints) {
  return distribution_of(
      seeds, level, metric.target, [&](const LevelFigures& l) { return metric.get(brdf ? l.brdf : l.param); },
      [&](const LevelFigures& l) { return !(without_glints && seed_in_glint_regime(l)); });
}

const std::vector<TransmissionMetric>& transmission_metrics() {
  static const std::vector<TransmissionMetric> metrics{
      {"e_log, transmitted", [](const TransmissionFigures& t) { return t.elog_transmitted; }},
      {"e_log, reflected", [](const TransmissionFigures& t) { return t.elog_reflected; }},
      {"|flux|, transmitted", [](const TransmissionFigures& t) { return std::abs(t.flux_transmitted); }},
      {"|flux|, reflected", [](const TransmissionFigures& t) { return std::abs(t.flux_reflected); }},
      {"|transmittance|", [](const TransmissionFigures& t) {
         return std::max({std::abs(t.transmittance[0]), std::abs(t.transmittance[1]), std::abs(t.transmittance[2])});
       }},
  };
  return metrics;
}

Distribution distribution(const std::vector<SeedFigures>& seeds, int level, const TransmissionMetric& metric) {
  return distribution_of(
      seeds, level, kNoTarget, [&](const LevelFigures& l) { return metric.get(l.transmission); },
      [](const LevelFigures& l) { return l.transmits; });
}

std::string family_table(const std::vector<SeedFigures>& seeds, int size) {
  std::string s = format("The random family at %dx%d, %zu seeds (textures/random_material.h):\n", size, size, seeds.size());
  for (const SeedFigures& seed : seeds) {
    s += "  " + seed.summary + "\n";
    // Where the seed misses a target.
    std::string misses;
    for (const LevelFigures& l : seed.levels)
      for (const FamilyMetric& m : family_metrics()) {
        const double v = m.get(l.brdf);
        if (v > m.target) misses += format(" L%d %s %.4f;", l.level, m.name, v);
      }
    if (!misses.empty()) s += "    brdf misses:" + misses + "\n";
    std::string transmission;
    for (const LevelFigures& l : seed.levels)
      if (l.transmits)
        transmission += format(" L%d e_log %.4f / %.4f, flux %+.2f / %+.2f %%, T %+.2f %+.2f %+.2f %%;", l.level,
                               l.transmission.elog_transmitted, l.transmission.elog_reflected,
                               100 * l.transmission.flux_transmitted, 100 * l.transmission.flux_reflected,
                               100 * l.transmission.transmittance[0], 100 * l.transmission.transmittance[1],
                               100 * l.transmission.transmittance[2]);
    if (!transmission.empty()) s += "    brdf transmitted / reflected:" + transmission + "\n";
  }
  s += format("\n%-5s %-24s %7s | %-42s | %-46s | %-23s\n", "level", "figure", "target",
              "brdf, all seeds: median p90 max (worst) meet", "brdf, seeds without glints: median p90 max (worst) meet",
              "param, all: median p90 max");
  const int last = last_level(seeds);
  for (int level = 1; level <= last; ++level)
    for (const FamilyMetric& m : family_metrics()) {
      const Distribution b = distribution(seeds, level, m, true), p = distribution(seeds, level, m, false);
      const Distribution c = distribution(seeds, level, m, true, true);
      if (b.count == 0 && p.count == 0) continue;
      const bool target = !std::isnan(m.target);
      const auto cells = [&](const Distribution& x) {
        if (x.count == 0) return format("%46s", "-");
        return format("%7.4f %7.4f %7.4f (%6llu) %8s", x.median, x.p90, x.max, static_cast<unsigned long long>(x.worst_seed),
                      target ? format("%d/%d", x.meeting, x.count).c_str() : "");
      };
      s += format("%-5d %-24s %7s | %s | %s | %7.4f %7.4f %7.4f\n", level, m.name, target ? format("%.3f", m.target).c_str() : "-",
                  cells(b).c_str(), cells(c).c_str(), p.median, p.p90, p.max);
    }
  std::string transmission;
  for (int level = 1; level <= last; ++level)
    for (const TransmissionMetric& m : transmission_metrics()) {
      const Distribution d = distribution(seeds, level, m);
      if (d.count == 0) continue;
      transmission += format("%-5d %-24s | %7.4f %7.4f %7.4f (%6llu) %5d\n", level, m.name, d.median, d.p90, d.max,
                             static_cast<unsigned long long>(d.worst_seed), d.count);
    }
  if (!transmission.empty())
    s += format("\n%-5s %-24s | %-37s\n", "level", "brdf, seeds that transmit", "median p90 max (worst) seeds") + transmission;
  s += "e_log, e_mean, e_rel: ../shared/spec/brdf-mip.md over the 4225 direction pairs (256 random texels where a level has "
       "more); e_rel glints: texels in the glint regime (apps/random_family_measure.h); seeds without glints: fewer than half "
       "their measured texels in it at the level; albedo: the largest error over θi 0°, 45°, 75°; transmitted and reflected: "
       "the same pairs, 4 × 4 texels a level (apps/transmission_figures.h), |flux| = |Σ L̂ / Σ L − 1|.\n";
  return s;
}

Json family_json(const std::vector<SeedFigures>& seeds, int size) {
  Json list = Json::array();
  for (const SeedFigures& seed : seeds) {
    Json levels = Json::array();
    for (const LevelFigures& l : seed.levels) {
      Json level = {{"level", l.level},
                    {"measured", l.measured},
                    {"glint", l.glint},
                    {"param", mode_json(l.param)},
                    {"brdf", mode_json(l.brdf)}};
      if (l.transmits)
        level["brdf_transmission"] = {{"e_log_transmitted", six_digits(l.transmission.elog_transmitted)},
                                      {"e_log_reflected", six_digits(l.transmission.elog_reflected)},
                                      {"flux_transmitted", six_digits(l.transmission.flux_transmitted)},
                                      {"flux_reflected", six_digits(l.transmission.flux_reflected)},
                                      {"transmittance", {six_digits(l.transmission.transmittance[0]),
                                                         six_digits(l.transmission.transmittance[1]),
                                                         six_digits(l.transmission.transmittance[2])}}};
      levels.push_back(std::move(level));
    }
    list.push_back({{"seed", seed.seed}, {"drew", seed.summary}, {"levels", std::move(levels)}});
  }
  Json dist = Json::array();
  const int last = last_level(seeds);
  for (int level = 1; level <= last; ++level)
    for (const FamilyMetric& m : family_metrics())
      for (int set = 0; set < 3; ++set) {
        const bool brdf = set < 2, without_glints = set == 1;
        const Distribution d = distribution(seeds, level, m, brdf, without_glints);
        dist.push_back({{"level", level},
                        {"figure", m.name},
                        {"mode", brdf ? "brdf" : "param"},
                        {"seeds_in_glint_regime", without_glints ? "left out" : "included"},
                        {"target", six_digits(m.target)},
                        {"count", d.count},
                        {"median", six_digits(d.median)},
                        {"p90", six_digits(d.p90)},
                        {"max", six_digits(d.max)},
                        {"worst_seed", d.worst_seed},
                        {"meeting", d.meeting}});
      }
  for (int level = 1; level <= last; ++level)
    for (const TransmissionMetric& m : transmission_metrics()) {
      const Distribution d = distribution(seeds, level, m);
      dist.push_back({{"level", level},
                      {"figure", m.name},
                      {"mode", "brdf"},
                      {"seeds", "transmitting"},
                      {"count", d.count},
                      {"median", six_digits(d.median)},
                      {"p90", six_digits(d.p90)},
                      {"max", six_digits(d.max)},
                      {"worst_seed", d.worst_seed}});
    }
  return {{"size", size}, {"seeds", std::move(list)}, {"distribution", std::move(dist)}};
}

}  // namespace svbrdf
