#include "mip/metrics.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "appearance/frame.h"
#include "appearance/rng.h"
#include "base/math.h"
#include "base/error.h"
#include "mip/exact_reference.h"
#include "mip/sheen_layer.h"

namespace svbrdf {

double e_rel(const BrdfTable& approx, const BrdfTable& exact) {
  const DirectionGrid& g = DirectionGrid::get();
  double num = 0, den = 0;
  for (int p = 0; p < DirectionGrid::kPairs; ++p) {
    const double cz = g.direction(DirectionGrid::wi_index(p)).z;
    const glm::dvec3 l = exact[static_cast<std::size_t>(p)] * cz;
    const glm::dvec3 d = approx[static_cast<std::size_t>(p)] * cz - l;
    num += glm::dot(d, d);
    den += glm::dot(l, l);
  }
  if (den == 0) return num == 0 ? 0.0 : INFINITY;
  return std::sqrt(num) / std::sqrt(den);
}

double e_log(const BrdfTable& approx, const BrdfTable& exact) {
  const DirectionGrid& g = DirectionGrid::get();
  double sum = 0;
  for (int p = 0; p < DirectionGrid::kPairs; ++p) {
    const double cz = g.direction(DirectionGrid::wi_index(p)).z;
    for (int c = 0; c < 3; ++c) {
      const double d = std::log1p(approx[static_cast<std::size_t>(p)][c] * cz) - std::log1p(exact[static_cast<std::size_t>(p)][c] * cz);
      sum += d * d;
    }
  }
  return std::sqrt(sum / (3.0 * DirectionGrid::kPairs));
}

std::vector<int> measured_texels(Extent e, int subset, std::uint64_t seed, int level) {
  const int n = e.width * e.height;
  std::vector<int> all(static_cast<std::size_t>(n));
  std::iota(all.begin(), all.end(), 0);
  if (subset <= 0 || n <= subset) return all;
  // A partial Fisher–Yates shuffle: the first `subset` entries are a uniform draw without replacement.
  Rng rng(mix64(seed), static_cast<std::uint64_t>(level) + 1);
  for (int k = 0; k < subset; ++k) {
    const int r = k + static_cast<int>(rng.next_double() * (n - k));
    std::swap(all[static_cast<std::size_t>(k)], all[static_cast<std::size_t>(std::min(r, n - 1))]);
  }
  all.resize(static_cast<std::size_t>(subset));
  std::sort(all.begin(), all.end());
  return all;
}

namespace {

double texel_area(Extent e0, int level, int i, int j) {
  return static_cast<double>(level0_span(e0.width, level, i).size()) * level0_span(e0.height, level, j).size();
}

// The area-weighted mean F of a whole level under a mode (not exact).
BrdfTable level_mean(const MipData& mip, TextureFilter mode, int level) {
  const Extent e = mip.extent(level), e0 = mip.extent(0);
  const double total = static_cast<double>(e0.width) * e0.height;
  BrdfTable sum = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<int>(0, e.width * e.height, 64), BrdfTable{},
      [&](const tbb::blocked_range<int>& r, BrdfTable acc) {
        if (acc.empty()) acc = make_table();
        for (int t = r.begin(); t < r.end(); ++t) {
          const int i = t % e.width, j = t / e.width;
          const double w = texel_area(e0, level, i, j) / total;
          if (mode == TextureFilter::brdf)
            accumulate_brdf_texel(mip, level, i, j, w, acc);
          else
            accumulate_param_texel(mip, mode, level, i, j, w, acc);
        }
        return acc;
      },
      [](BrdfTable a, const BrdfTable& b) {
        if (a.empty()) return b;
        if (b.empty()) return a;
        for (std::size_t k = 0; k < a.size(); ++k) a[k] += b[k];
        return a;
      });
  return sum;
}

}  // namespace

std::vector<LevelComparison> compare_levels(const MipData& mip, const CompareOptions& o) {
  const int n = mip.levels();
  const int first = o.first_level, last = o.last_level < 0 ? n - 1 : o.last_level;
  if (first < 0 || last >= n || first > last)
    throw input_error("--levels", std::to_string(first) + ".." + std::to_string(last) +
                                      " is not a range of the file's levels 0.." + std::to_string(n - 1));
  for (TextureFilter mode : o.modes)
    if (mode == TextureFilter::level0) throw input_error("level0", "stores no coarse texel to compare");
  const Extent e0 = mip.extent(0);
  const ExactReference exact(mip.level0);
  auto count = [&](int level) { return mip.extent(level).width * mip.extent(level).height; };
  // The first level measured in full; the exact tables of it and of every coarser level.
  int full = 0;
  while (count(full) > std::max(1, o.subset)) ++full;
  std::vector<std::vector<BrdfTable>> full_tables(static_cast<std::size_t>(n));
  {
    const Extent e = mip.extent(full);
    auto& tabs = full_tables[static_cast<std::size_t>(full)];
    tabs.resize(static_cast<std::size_t>(count(full)));
    tbb::parallel_for(0, count(full), [&](int t) {
      tabs[static_cast<std::size_t>(t)] = exact.table(full, t % e.width, t / e.width);
    });
    for (int level = full + 1; level < n; ++level) {
      const Extent c = mip.extent(level), f = mip.extent(level - 1);
      auto& out = full_tables[static_cast<std::size_t>(level)];
      out.assign(static_cast<std::size_t>(count(level)), make_table());
      for (int j = 0; j < c.height; ++j)
        for (int i = 0; i < c.width; ++i) {
          const Span cx = child_span(e0.width, level, i), cy = child_span(e0.height, level, j);
          const double area = texel_area(e0, level, i, j);
          BrdfTable& t = out[static_cast<std::size_t>(j * c.width + i)];
          for (int y = cy.begin; y < cy.end; ++y)
            for (int x = cx.begin; x < cx.end; ++x) {
              const double w = texel_area(e0, level - 1, x, y) / area;
              const BrdfTable& child = full_tables[static_cast<std::size_t>(level - 1)][static_cast<std::size_t>(y * f.width + x)];
              for (std::size_t k = 0; k < t.size(); ++k) t[k] += w * child[k];
            }
        }
    }
  }
  const BrdfTable& texture_mean = full_tables[static_cast<std::size_t>(n - 1)][0];

  std::vector<LevelComparison> out;
  for (int level = first; level <= last; ++level) {
    LevelComparison lc;
    lc.level = level;
    lc.extent = mip.extent(level);
    const std::vector<int> texels = measured_texels(lc.extent, level >= full ? 0 : o.subset, o.seed, level);
    lc.measured = static_cast<int>(texels.size());
    lc.subset = lc.measured < count(level);
    std::vector<BrdfTable> ref(texels.size());
    tbb::parallel_for(std::size_t(0), texels.size(), [&](std::size_t k) {
      const int t = texels[k];
      ref[k] = level >= full ? full_tables[static_cast<std::size_t>(level)][static_cast<std::size_t>(t)]
                             : exact.table(level, t % lc.extent.width, t / lc.extent.width);
    });
    for (TextureFilter mode : o.modes) {
      ModeLevelStats s;
      s.mode = mode;
      s.bytes_per_texel = bytes_per_texel(mip, mode, level);
      std::vector<double> er(texels.size()), el(texels.size());
      tbb::parallel_for(std::size_t(0), texels.size(), [&](std::size_t k) {
        const int t = texels[k];
        const BrdfTable approx = texel_table(mip, mode, level, t % lc.extent.width, t / lc.extent.width);
        er[k] = e_rel(approx, ref[k]);
        el[k] = e_log(approx, ref[k]);
      });
      for (std::size_t k = 0; k < texels.size(); ++k) {
        s.erel_mean += er[k];
        s.erel_max = std::max(s.erel_max, er[k]);
        s.elog_mean += el[k];
      }
      s.erel_mean /= static_cast<double>(texels.size());
      s.elog_mean /= static_cast<double>(texels.size());
      s.emean = e_rel(level_mean(mip, mode, level), texture_mean);
      lc.modes.push_back(s);
    }
    out.push_back(std::move(lc));
  }
  return out;
}

namespace {

// ∫ f(wo)·wo.z dwo of one lobe's term f, importance-sampled by the lobe's shape (directional_albedo).
template <class F>
glm::dvec3 lobe_albedo(const Lobe& l, const glm::dvec3& wi, int strata, const F& f_of) {
  const glm::dvec3 n = glm::normalize(glm::dvec3(l.normal));
  const Frame fr = Frame::from_normal(glm::vec3(n));
  const glm::dvec3 s(fr.s), t(fr.t);
  const LobeShape<double> shape = lobe_shape<double>(l);
  const double a2 = shape.alpha2;
  // Densities over wo: cosine about the geometric normal, and wo = reflect(wi) about h ~ D(h)·(n·h),
  // D the lobe's own (lobe.h).
  auto pdf_cos = [&](const glm::dvec3& wo) { return wo.z > 0 ? wo.z / kPiD : 0.0; };
  auto pdf_spec = [&](const glm::dvec3& wo) {
    const glm::dvec3 h = glm::normalize(wi + wo);
    const double ch = glm::dot(n, h), oh = glm::dot(wo, h);
    if (ch <= 0 || oh <= 0) return 0.0;
    return lobe_d(shape, ch, glm::cross(n, h)) * ch / (4 * oh);
  };
  const int m = strata * strata;
  glm::dvec3 sum(0);
  for (int technique = 0; technique < 2; ++technique)
    for (int k = 0; k < m; ++k) {
      // A fixed jittered grid (Rng with a fixed seed), so the quadrature is deterministic.
      Rng rng(mix64(static_cast<std::uint64_t>(k) * 2 + technique), 11);
      const double u1 = ((k % strata) + rng.next_double()) / strata, u2 = ((k / strata) + rng.next_double()) / strata;
      glm::dvec3 wo;
      if (technique == 0) {
        const double r = std::sqrt(u1), phi = 2 * kPiD * u2;
        wo = glm::dvec3(r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0, 1 - u1)));
      } else {
        // t = tan²θh with density D(h)·cosθh: GGX t = α²·u/(1 − u) (Walter et al. 2007, eq. 35/36),
        // Beckmann t = −α²·ln(1 − u) (eq. 28), chosen in the lobe's shares; a roughness mixture's
        // band by inverting its CDF ln(h(l + t)/(l(h + t)))/ln(h/l) = u, its atoms as GGX.
        double tan2;
        if (shape.alpha2_hi > 0) {
          const double lo = a2, hi = shape.alpha2_hi;
          if (rng.next_double() >= shape.ggx) {
            tan2 = lo * u1 / std::max(1e-300, 1 - u1);
          } else if (shape.two_point) {
            tan2 = hi * u1 / std::max(1e-300, 1 - u1);
          } else {
            const double r = std::pow(hi / lo, u1);
            tan2 = hi * lo * (r - 1) / std::max(1e-300, hi - r * lo);
          }
        } else if (rng.next_double() >= shape.ggx) {
          tan2 = -a2 * std::log1p(-std::min(u1, 1 - 1e-16));
        } else {
          tan2 = a2 * u1 / std::max(1e-300, 1 - u1);
        }
        const double ch = 1 / std::sqrt(1 + tan2), sh = std::sqrt(std::max(0.0, 1 - ch * ch)), phi = 2 * kPiD * u2;
        glm::dvec3 h = sh * std::cos(phi) * s + sh * std::sin(phi) * t + ch * n;
        if (shape.stretched) {
          // A stretched shape's slopes are the isotropic ones times S^(1/2) in its frame (lobe.h), a
          // map of determinant 1: the same density D·(n·h) of its own half vectors.
          const double tn = std::sqrt(tan2);
          h = glm::normalize(tn * std::sqrt(shape.r) * std::cos(phi) * shape.st +
                             tn * std::sqrt(shape.inv_r) * std::sin(phi) * shape.sb + n);
        }
        wo = 2 * glm::dot(wi, h) * h - wi;
      }
      if (!(wo.z > 0)) continue;
      const double q = m * pdf_cos(wo) + m * pdf_spec(wo);
      if (!(q > 0)) continue;
      sum += f_of(pair_terms<double>(wi, wo)) * wo.z / q;
    }
  return sum;
}

}  // namespace

glm::dvec3 directional_albedo(std::span<const Lobe> lobes, const glm::dvec3& wi, int strata) {
  glm::dvec3 total(0);
  for (const Lobe& l : lobes)
    if (l.weight > 0) total += lobe_albedo(l, wi, strata, [&](const PairTerms<double>& p) { return lobe_eval<double>(l, p); });
  return total;
}

glm::dvec3 directional_albedo(std::span<const Lobe> base, const CoatTexel& coat, const glm::dvec3& wi, int strata) {
  if (!coat.present()) return directional_albedo(base, wi, strata);
  glm::dvec3 total(0);
  for (const Lobe& l : base)
    if (l.weight > 0)
      total += lobe_albedo(l, wi, strata, [&](const PairTerms<double>& p) {
        return (1.0 - l.coat * coat_fresnel(coat, p.wo)) * lobe_eval<double>(l, p);
      });
  std::array<LobeShape<double>, kMaxLobes> shapes;
  const std::size_t n = std::min<std::size_t>(base.size(), kMaxLobes);
  for (std::size_t k = 0; k < n; ++k) shapes[k] = lobe_shape<double>(base[k], false);
  for (const Lobe& l : coat.lobes)
    if (l.weight > 0) {
      const LobeShape<double> s = lobe_shape<double>(l);
      total += lobe_albedo(l, wi, strata, [&](const PairTerms<double>& p) {
        return coat_cosine(base.first(n), shapes.data(), p) * coat_lobe_eval(l, s, p);
      });
    }
  return total;
}

glm::dvec3 directional_albedo(std::span<const Lobe> base, const SheenLayer& sheen, const glm::dvec3& wi, int strata) {
  float shares = 0;
  for (const Lobe& l : base) shares += l.weight * l.sheen;
  if (!(shares > 0)) return directional_albedo(base, wi, strata);
  const glm::vec3 scale = sheen.color / shares;  // as LobeMixtureBsdf::set_sheen
  glm::dvec3 total(0);
  for (const Lobe& l : base)
    if (l.weight > 0) {
      const LobeShape<float> s = lobe_shape<float>(l);
      total += lobe_albedo(l, wi, strata, [&](const PairTerms<double>& p) {
        const PairTerms<float> q = pair_terms<float>(glm::vec3(p.wi), glm::vec3(p.wo));
        float sides;
        const glm::vec3 f = lobe_eval(l, s, q, 1.0f, &sides);
        const SheenLobeTerms t = sheen_lobe_terms(l, s, q, sides, sheen.roughness);
        return glm::dvec3(t.scaling * f + t.sheen * scale);
      });
    }
  return total;
}

}  // namespace svbrdf
