#include "apps/transmission_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "base/math.h"
#include "mip/mip.h"

namespace svbrdf {

namespace {

std::vector<glm::dvec3> directions() {
  std::vector<glm::dvec3> d{{0, 0, 1}};
  for (int t = 20; t <= 80; t += 20)
    for (int p = 0; p < 360; p += 45) {
      const double th = t * kPiD / 180, ph = p * kPiD / 180;
      d.push_back({std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)});
    }
  return d;
}

// One side's sums over the pairs and channels.
struct Side {
  double sq = 0, n = 0, got = 0, want = 0;
  void add(const glm::dvec3& f_got, const glm::dvec3& f_want, double cos_i) {
    for (int c = 0; c < 3; ++c) {
      const double a = f_got[c] * cos_i, b = f_want[c] * cos_i;
      const double d = std::log1p(a) - std::log1p(b);
      sq += d * d, n += 1, got += a, want += b;
    }
  }
  double elog() const { return std::sqrt(sq / n); }
  double flux() const { return got / want - 1; }
};

}  // namespace

std::vector<TransmissionFigures> measure_transmission(const MipData& mip) {
  static const std::vector<glm::dvec3> dirs = directions();
  const std::size_t pairs = dirs.size() * dirs.size();
  const Extent e0 = mip.extent(0);
  const ExactReference exact(mip.level0);
  std::vector<TransmissionFigures> out;
  // The exact values (reflected pairs, then transmitted) of every texel of the previous level, where
  // all of its texels were measured.
  std::vector<std::vector<glm::dvec3>> finer;
  Extent finer_extent{};
  for (int level = 1; level < mip.levels(); ++level) {
    const Extent e = mip.extent(level);
    const int step_x = std::max(1, e.width / 4), step_y = std::max(1, e.height / 4);
    const bool all = step_x == 1 && step_y == 1;
    const bool derive = all && !finer.empty();
    std::vector<std::vector<glm::dvec3>> here(all ? std::size_t(e.width) * e.height : 0);
    Side reflected, transmitted;
    for (int j = 0; j < e.height; j += step_y)
      for (int i = 0; i < e.width; i += step_x) {
        std::vector<glm::dvec3> want(2 * pairs, glm::dvec3(0));
        if (derive) {
          // The coverage-weighted mean of the finer level's texels that make this one.
          const Span cols = child_span(e0.width, level, i), rows = child_span(e0.height, level, j);
          double total = 0;
          for (int y = rows.begin; y < rows.end; ++y)
            for (int x = cols.begin; x < cols.end; ++x) {
              const double w = double(coverage(e0, level - 1, x, y).count());
              const std::vector<glm::dvec3>& c = finer[std::size_t(y) * finer_extent.width + x];
              for (std::size_t p = 0; p < want.size(); ++p) want[p] += w * c[p];
              total += w;
            }
          for (glm::dvec3& v : want) v /= total;
        } else {
          for (std::size_t a = 0; a < dirs.size(); ++a)
            for (std::size_t b = 0; b < dirs.size(); ++b) {
              const glm::dvec3 &wi = dirs[a], &wo = dirs[b], below(wi.x, wi.y, -wi.z);
              want[a * dirs.size() + b] = exact.eval(level, i, j, wi, wo);
              want[pairs + a * dirs.size() + b] = exact.eval(level, i, j, below, wo);
            }
        }
        Lobe scratch, coat_scratch;
        LobeMixtureBsdf bsdf(brdf_texel(mip, level, i, j, scratch), brdf_coat(mip, level, i, j, coat_scratch).lobes);
        if (const SheenLayer* s = brdf_sheen(mip, level, i, j)) bsdf.set_sheen(*s);
        for (std::size_t a = 0; a < dirs.size(); ++a)
          for (std::size_t b = 0; b < dirs.size(); ++b) {
            const glm::vec3 wi(dirs[a]), wo(dirs[b]), below(wi.x, wi.y, -wi.z);
            reflected.add(glm::dvec3(bsdf.eval(wi, wo)), want[a * dirs.size() + b], dirs[a].z);
            transmitted.add(glm::dvec3(bsdf.eval(below, wo)), want[pairs + a * dirs.size() + b], dirs[a].z);
          }
        if (all) here[std::size_t(j) * e.width + i] = std::move(want);
      }
    finer = std::move(here);
    finer_extent = e;
    TransmissionFigures f;
    f.elog_reflected = reflected.elog();
    f.elog_transmitted = transmitted.elog();
    f.flux_reflected = reflected.flux();
    f.flux_transmitted = transmitted.want > 0 ? transmitted.flux() : std::numeric_limits<double>::quiet_NaN();
    f.exact_transmitted = transmitted.want;
    out.push_back(f);
  }
  return out;
}

}  // namespace svbrdf
