#pragma once
// One pyramid's figures at every level ≥ 1 against the exact reference (mip/exact_reference.h): the
// spec's e_log and e_mean, and the directional albedo's relative error at θi 0°, 45°, 75°, of each
// level's total and per texel, each texel under its sheen where the material has one. For the layer
// tests, which hold a layer's pyramid to its layerless twin's figures.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <span>
#include <vector>

#include "mip/exact_reference.h"
#include "mip/metrics.h"
#include "mip/mip_data.h"

namespace svbrdf::testing_figures {

// One level's figures against the exact reference: e_log, e_mean, and the directional albedo's
// relative error at θi 0°, 45°, 75°, of the level's total and per texel (Σ|texel − exact| / Σ exact).
struct Figures {
  double elog, emean;
  std::array<double, 3> total, texel;
};

inline std::vector<Figures> measure(const MipData& mip) {
  CompareOptions o;
  o.modes = {TextureFilter::brdf};
  o.subset = 64;
  const MaterialTexels& m = mip.level0;
  constexpr std::array<double, 3> kTheta{0, 45, 75};
  constexpr double kPi = 3.14159265358979323846;
  constexpr int kStrata = 12;
  const auto incident = [&](std::size_t a) {
    const double t = kTheta[a] * kPi / 180;
    return glm::dvec3(std::sin(t), 0.0, std::cos(t));
  };
  // The exact albedo of a coarse texel is the mean of its level-0 texels' (linear in the texels).
  std::vector<std::array<double, 3>> albedo0(m.size());
  for (std::size_t k = 0; k < m.size(); ++k) {
    const Lobe l = level0_lobe(m, k);
    for (std::size_t a = 0; a < 3; ++a)
      albedo0[k][a] = directional_albedo(std::span<const Lobe>(&l, 1), m.sheen_layer(k), incident(a), kStrata).g;
  }
  std::vector<Figures> out;
  for (const LevelComparison& row : compare_levels(mip, o)) {
    Figures f{row.modes[0].elog_mean, row.modes[0].emean, {}, {}};
    const Extent e = row.extent;
    for (std::size_t a = 0; a < 3; ++a) {
      double exact_sum = 0, got_sum = 0, abs_sum = 0;
      for (int j = 0; j < e.height; ++j)
        for (int i = 0; i < e.width; ++i) {
          const Coverage c = coverage(mip.extent(0), row.level, i, j);
          double exact = 0;
          for (int y = c.rows.begin; y < c.rows.end; ++y)
            for (int x = c.columns.begin; x < c.columns.end; ++x) exact += albedo0[m.index(x, y)][a];
          exact /= double(c.count());
          const SheenLayer sheen = mip.brdf.has_sheen() ? mip.brdf.sheen(row.level, i, j) : SheenLayer{};
          const double got = directional_albedo(mip.brdf.texel(row.level, i, j), sheen, incident(a), kStrata).g;
          exact_sum += exact, got_sum += got, abs_sum += std::abs(got - exact);
        }
      f.total[a] = got_sum / exact_sum - 1;
      f.texel[a] = abs_sum / exact_sum;
    }
    out.push_back(f);
  }
  return out;
}

// A layer's figures at one level against its layerless twin's: printed (with the two pyramids' bytes
// a texel), and the layer may add at most `d_elog` to e_log, `d_emean` to e_mean and `d_albedo` to
// each albedo error. The caller's SCOPED_TRACE names the seed and level.
inline void expect_within_twin(std::uint64_t seed, int level, const Figures& s, const Figures& t, int bytes,
                               int twin_bytes, double d_elog, double d_emean, double d_albedo) {
  std::printf("seed %3llu level %d  e_log %.4f (%.4f)  e_mean %.4f (%.4f)  albedo total 0/45/75° %+.2f/%+.2f/%+.2f %% "
              "(%+.2f/%+.2f/%+.2f)  per texel %.2f/%.2f/%.2f %% (%.2f/%.2f/%.2f)  B/texel %d (%d)\n",
              static_cast<unsigned long long>(seed), level, s.elog, t.elog, s.emean, t.emean, 100 * s.total[0],
              100 * s.total[1], 100 * s.total[2], 100 * t.total[0], 100 * t.total[1], 100 * t.total[2],
              100 * s.texel[0], 100 * s.texel[1], 100 * s.texel[2], 100 * t.texel[0], 100 * t.texel[1],
              100 * t.texel[2], bytes, twin_bytes);
  EXPECT_LE(s.elog, t.elog + d_elog);
  EXPECT_LE(s.emean, t.emean + d_emean);
  for (std::size_t a = 0; a < 3; ++a) {
    EXPECT_LE(std::abs(s.total[a]), std::abs(t.total[a]) + d_albedo) << "albedo total, " << a;
    EXPECT_LE(s.texel[a], t.texel[a] + d_albedo) << "albedo per texel, " << a;
  }
}

}  // namespace svbrdf::testing_figures
