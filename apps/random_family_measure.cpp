#include "apps/random_family_measure.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "base/math.h"
#include "mip/metrics.h"

namespace svbrdf {

bool in_glint_regime(const MaterialTexels& m, int level, int i, int j) {
  const Coverage c = coverage({m.width, m.height}, level, i, j);
  glm::dvec3 sum(0);
  double alpha2 = 0;
  long long glossy = 0;
  for (int y = c.rows.begin; y < c.rows.end; ++y)
    for (int x = c.columns.begin; x < c.columns.end; ++x) {
      const std::size_t k = m.index(x, y);
      if (!(m.roughness[k] < kGlintRoughness)) continue;
      sum += glm::dvec3(m.normal[k]);
      const double a = std::max(double(m.roughness[k]) * m.roughness[k], 1e-3);
      alpha2 += a * a;
      ++glossy;
    }
  if (glossy < 2) return false;
  const glm::dvec3 mean = glm::normalize(sum);
  double angle2 = 0;
  for (int y = c.rows.begin; y < c.rows.end; ++y)
    for (int x = c.columns.begin; x < c.columns.end; ++x) {
      const std::size_t k = m.index(x, y);
      if (!(m.roughness[k] < kGlintRoughness)) continue;
      const double a = std::acos(std::clamp(glm::dot(glm::dvec3(m.normal[k]), mean), -1.0, 1.0));
      angle2 += a * a;
    }
  const double spread = std::sqrt(angle2 / double(glossy));
  return spread > 0 && spread * spread >= alpha2 / double(glossy);
}

namespace {

// 16² strata per technique, as the preset tests take the albedo; a quadrature error common to a texel
// and its exact value (the same lobes, the same samples at level 1) largely cancels in the ratio.
constexpr int kAlbedoStrata = 16;

glm::dvec3 incident(int t) {
  const double theta = kAlbedoThetaDeg[static_cast<std::size_t>(t)] * kPiD / 180.0;
  return {std::sin(theta), 0.0, std::cos(theta)};
}

// One number per albedo: the channels' mean (a channel near zero would make its own relative error
// meaningless).
double grey(const glm::dvec3& c) { return (c.r + c.g + c.b) / 3.0; }

// The albedo figures of one mode at a level: `texel_albedo(i, j, t)` the mode's, `exact` per texel and θi.
template <class Albedo>
void albedo_figures(Extent e0, int level, Extent e, const std::vector<std::array<double, 3>>& exact, Albedo texel_albedo,
                    ModeFigures& out) {
  std::vector<std::array<double, 3>> got(exact.size());
  tbb::parallel_for(0, e.width * e.height, [&](int t) {
    for (int a = 0; a < 3; ++a) got[std::size_t(t)][std::size_t(a)] = texel_albedo(t % e.width, t / e.width, a);
  });
  for (std::size_t a = 0; a < 3; ++a) {
    double total_exact = 0, total = 0, total_abs = 0;
    for (int t = 0; t < e.width * e.height; ++t) {
      const double area = double(coverage(e0, level, t % e.width, t / e.width).count());
      total_exact += area * exact[std::size_t(t)][a];
      total += area * got[std::size_t(t)][a];
      total_abs += area * std::abs(got[std::size_t(t)][a] - exact[std::size_t(t)][a]);
    }
    out.albedo_total[a] = total / total_exact - 1;
    out.albedo_texel[a] = total_abs / total_exact;
  }
}

}  // namespace

SeedFigures measure_random_seed(std::uint64_t seed, int size, const BrdfBuildOptions& build) {
  return measure_random_draw(draw_random_material(seed), size, build);
}

SeedFigures measure_random_draw(const RandomMaterialDraw& draw, int size, const BrdfBuildOptions& build) {
  SeedFigures out;
  out.seed = draw.seed;
  out.summary = draw.summary();
  const MipData mip = build_mip(random_material_texels(draw, size), build);
  const MaterialTexels& m = mip.level0;
  const Extent e0 = mip.extent(0);
  if (mip.levels() < 2) return out;

  CompareOptions co;
  co.modes = {TextureFilter::param, TextureFilter::brdf};
  const std::vector<LevelComparison> rows = compare_levels(mip, co);

  // Level-0 albedo per texel and θi, once: a coarse texel's exact albedo is the mean of its texels'.
  std::vector<std::array<double, 3>> albedo0(m.size());
  tbb::parallel_for(std::size_t(0), m.size(), [&](std::size_t k) {
    const Lobe l = level0_lobe(m, k);
    const SheenLayer sheen = m.sheen_layer(k);  // colour 0 without a sheen: the lobe alone
    for (int a = 0; a < 3; ++a)
      albedo0[k][std::size_t(a)] = grey(directional_albedo(std::span<const Lobe>(&l, 1), sheen, incident(a), kAlbedoStrata));
  });

  const ExactReference exact(m);
  const std::vector<TransmissionFigures> transmission =
      m.has_transmission() ? measure_transmission(mip) : std::vector<TransmissionFigures>{};
  for (const LevelComparison& row : rows) {
    LevelFigures f;
    f.level = row.level;
    f.measured = row.measured;
    const Extent e = row.extent;
    for (int which = 0; which < 2; ++which) {
      const ModeLevelStats& s = row.modes[std::size_t(which)];
      ModeFigures& mf = which == 0 ? f.param : f.brdf;
      mf.elog_mean = s.elog_mean;
      mf.emean = s.emean;
      mf.erel_mean = s.erel_mean;
      mf.erel_max = s.erel_max;
    }

    // e_rel of the measured texels in the glint regime (the same texels compare_levels drew); the
    // others' mean follows from the level's.
    const std::vector<int> measured = measured_texels(e, co.subset, co.seed, row.level);
    std::vector<int> glint;
    for (int t : measured)
      if (in_glint_regime(m, row.level, t % e.width, t / e.width)) glint.push_back(t);
    f.glint = int(glint.size());
    std::vector<std::array<double, 2>> erel(glint.size());
    tbb::parallel_for(std::size_t(0), glint.size(), [&](std::size_t k) {
      const int i = glint[k] % e.width, j = glint[k] / e.width;
      const BrdfTable ref = exact.table(row.level, i, j);
      erel[k] = {e_rel(texel_table(mip, TextureFilter::param, row.level, i, j), ref),
                 e_rel(texel_table(mip, TextureFilter::brdf, row.level, i, j), ref)};
    });
    const double n = double(measured.size()), g = double(glint.size());
    const double nan = std::numeric_limits<double>::quiet_NaN();
    for (int which = 0; which < 2; ++which) {
      ModeFigures& mf = which == 0 ? f.param : f.brdf;
      double sum = 0;
      for (const auto& r : erel) sum += r[std::size_t(which)];
      mf.erel_mean_glint = g > 0 ? sum / g : nan;
      mf.erel_mean_other = n > g ? std::max(0.0, (mf.erel_mean * n - sum) / (n - g)) : nan;
    }

    // Directional albedo, every texel of the level.
    std::vector<std::array<double, 3>> exact_albedo(std::size_t(e.width) * e.height);
    for (int t = 0; t < e.width * e.height; ++t) {
      const Coverage c = coverage(e0, row.level, t % e.width, t / e.width);
      std::array<double, 3> sum{};
      for (int y = c.rows.begin; y < c.rows.end; ++y)
        for (int x = c.columns.begin; x < c.columns.end; ++x)
          for (std::size_t a = 0; a < 3; ++a) sum[a] += albedo0[m.index(x, y)][a];
      for (std::size_t a = 0; a < 3; ++a) exact_albedo[std::size_t(t)][a] = sum[a] / double(c.count());
    }
    albedo_figures(e0, row.level, e, exact_albedo,
                   [&](int i, int j, int a) {
                     const float* transmission = mip.param.transmission(row.level, i, j);
                     const ParamLobes l = param_lobes(mip.param.texel(row.level, i, j), TextureFilter::param,
                                                      mip.param.specular(row.level, i, j), nullptr,
                                                      mip.param.sheen(row.level, i, j),
                                                      mip.param.anisotropy(row.level, i, j),
                                                      transmission ? *transmission : 0.0f,
                                                      mip.param.diffuse_transmission(row.level, i, j));
                     return grey(directional_albedo(std::span<const Lobe>(&l.base, 1), l.sheen, incident(a), kAlbedoStrata));
                   },
                   f.param);
    albedo_figures(e0, row.level, e, exact_albedo,
                   [&](int i, int j, int a) {
                     const SheenLayer sheen = mip.brdf.has_sheen() ? mip.brdf.sheen(row.level, i, j) : SheenLayer{};
                     return grey(directional_albedo(mip.brdf.texel(row.level, i, j), sheen, incident(a), kAlbedoStrata));
                   },
                   f.brdf);
    if (m.has_transmission()) {
      f.transmits = true;
      f.transmission = transmission[std::size_t(row.level - 1)];
    }
    out.levels.push_back(std::move(f));
  }
  return out;
}

}  // namespace svbrdf
