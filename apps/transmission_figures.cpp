#include "apps/transmission_figures.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <tbb/parallel_for.h>

#include "appearance/rng.h"
#include "base/math.h"
#include "mip/mip.h"

namespace svbrdf {

namespace {

// A direction h about a transmission shape with density D(h)·(n̂·h) (lobe.h's D): tan²θh by inverting
// GGX's CDF (Walter et al. 2007, eq. 35/36) or the band's, ln(h(l + t)/(l(h + t)))/ln(h/l) = u; a
// stretched shape's slopes are the isotropic ones times S^(1/2) in its frame, a map of determinant 1
// that keeps the density (as mip/metrics.cpp's lobe_albedo draws).
glm::dvec3 sample_half_vector(const LobeShape<double>& s, double u1, double u2) {
  double tan2;
  if (s.alpha2_hi > 0) {
    const double lo = s.alpha2, hi = s.alpha2_hi, r = std::pow(hi / lo, u1);
    tan2 = hi * lo * (r - 1) / std::max(1e-300, hi - r * lo);
  } else {
    tan2 = s.alpha2 * u1 / std::max(1e-300, 1 - u1);
  }
  const double tn = std::sqrt(tan2), phi = 2 * kPiD * u2;
  const glm::dvec3 t = glm::normalize(glm::cross(std::abs(s.n.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0), s.n));
  const glm::dvec3 b = glm::cross(s.n, t);
  if (s.stretched)
    return glm::normalize(tn * std::sqrt(s.r) * std::cos(phi) * s.st + tn * std::sqrt(s.inv_r) * std::sin(phi) * s.sb + s.n);
  return glm::normalize(tn * std::cos(phi) * t + tn * std::sin(phi) * b + s.n);
}


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

// The mixture of texel (i, j) of `level`, as the renderer evaluates it (coat and sheen included).
LobeMixtureBsdf texel_mixture(const MipData& mip, int level, int i, int j) {
  Lobe scratch, coat_scratch;
  LobeMixtureBsdf bsdf(brdf_texel(mip, level, i, j, scratch), brdf_coat(mip, level, i, j, coat_scratch).lobes);
  if (const SheenLayer* s = brdf_sheen(mip, level, i, j)) bsdf.set_sheen(*s);
  return bsdf;
}

// Σ over the texels of `level` of their T at each θ, area-weighted (a texel of level L covers 4^L of
// level 0's, fewer at an odd edge: coverage()).
std::array<double, 3> level_transmittance(const MipData& mip, int level) {
  const Extent e = mip.extent(level), e0 = mip.extent(0);
  const long long texels = (long long)e.width * e.height;
  const int n = std::max(16, int(std::ceil(std::sqrt(double(kTransmittanceSamples) / double(texels)))));
  std::vector<std::array<double, 3>> per(std::size_t(texels), std::array<double, 3>{});
  tbb::parallel_for(0LL, texels, [&](long long t) {
    const int i = int(t % e.width), j = int(t / e.width);
    const LobeMixtureBsdf bsdf = texel_mixture(mip, level, i, j);
    if (!bsdf.has_transmission()) return;
    const double area = double(coverage(e0, level, i, j).count());
    for (std::size_t a = 0; a < 3; ++a) {
      const double th = kAlbedoThetaDeg[a] * kPiD / 180;
      const glm::dvec3 wi(std::sin(th), 0.0, -std::cos(th));
      per[std::size_t(t)][a] = area * directional_transmittance(bsdf, wi, n, mix64(std::uint64_t(t) * 3 + a));
    }
  });
  std::array<double, 3> total{};
  for (const auto& p : per)
    for (std::size_t a = 0; a < 3; ++a) total[a] += p[a];
  return total;
}

}  // namespace

double directional_transmittance(const LobeMixtureBsdf& bsdf, const glm::dvec3& wi, int n, std::uint64_t stream) {
  std::vector<LobeShape<double>> shapes;
  for (int k = 0; k < bsdf.size(); ++k)
    if (transmits(bsdf.lobe(k))) shapes.push_back(transmission_shape(bsdf.lobe(k), lobe_shape<double>(bsdf.lobe(k))));
  const auto mirrored = [&](const LobeShape<double>& s) { return wi - 2 * glm::dot(s.n, wi) * s.n; };
  // Σ over the techniques of n²·density at wo.
  const auto density = [&](const glm::dvec3& wo) {
    double q = wo.z / kPiD;
    for (const LobeShape<double>& s : shapes) {
      const glm::dvec3 h = glm::normalize(mirrored(s) + wo);
      const double ch = glm::dot(s.n, h), oh = std::abs(glm::dot(wo, h));
      if (ch > 0 && oh > 0) q += lobe_d(s, ch, glm::cross(s.n, h)) * ch / (4 * oh);
    }
    return q * n * n;
  };
  Rng rng(stream, 13);
  double sum = 0;
  for (std::size_t technique = 0; technique <= shapes.size(); ++technique)
    for (int k = 0; k < n * n; ++k) {
      const double u1 = (k % n + rng.next_double()) / n, u2 = (k / n + rng.next_double()) / n;
      glm::dvec3 wo;
      if (technique == 0) {
        const double r = std::sqrt(u1), phi = 2 * kPiD * u2;
        wo = glm::dvec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1)));
      } else {
        const LobeShape<double>& s = shapes[technique - 1];
        const glm::dvec3 h = sample_half_vector(s, u1, u2), w = mirrored(s);
        // Where w·h ≤ 0, h is not normalize(w + wo), the half vector `density` finds for wo: such a
        // sample is dropped, and the technique's density is that of the others it keeps.
        if (!(glm::dot(w, h) > 0)) continue;
        wo = 2 * glm::dot(w, h) * h - w;
      }
      if (!(wo.z > 0)) continue;
      const double q = density(wo);
      if (!(q > 0)) continue;
      const Rgb f = bsdf.eval(glm::vec3(wi), glm::vec3(wo));
      sum += (double(f.r) + f.g + f.b) / 3 * wo.z / q;
    }
  return sum;
}

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
  const std::array<double, 3> exact_t = level_transmittance(mip, 0);
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
        const LobeMixtureBsdf bsdf = texel_mixture(mip, level, i, j);
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
    const std::array<double, 3> got = level_transmittance(mip, level);
    for (std::size_t a = 0; a < 3; ++a)
      f.transmittance[a] = exact_t[a] > 0 ? got[a] / exact_t[a] - 1 : std::numeric_limits<double>::quiet_NaN();
    out.push_back(f);
  }
  return out;
}

}  // namespace svbrdf
