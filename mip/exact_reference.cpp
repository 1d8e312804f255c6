#include "mip/exact_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "mip/sheen_layer.h"

namespace svbrdf {

glm::dvec3 level0_eval(const MaterialTexels& m, std::size_t k, const PairTerms<double>& p) {
  Lobe scratch;
  const Lobe base = level0_lobe(m, k);
  glm::dvec3 f = lobe_eval<double>(base, p);
  if (m.has_sheen()) {
    const SheenTerms s = sheen_terms(m.sheen_layer(k), glm::normalize(glm::dvec3(base.normal)), p);
    f = s.scaling * f + s.f;
  }
  return coated_eval(f, double(base.coat) * f, {&base, 1}, level0_coat(m, k, scratch), p);
}

glm::dvec3 level0_transmission_eval(const MaterialTexels& m, std::size_t k, const glm::dvec3& wi, const glm::dvec3& wo) {
  if (!m.has_transmission() && !m.has_diffuse_transmission()) return glm::dvec3(0);
  const Lobe base = level0_lobe(m, k);
  const LobeShape<double> s = lobe_shape<double>(base);
  glm::dvec3 f = lobe_transmission_eval<double>(base, s, wi, wo) + lobe_diffuse_transmission_eval<double>(base, s, wi, wo);
  if (f == glm::dvec3(0)) return f;
  if (m.has_sheen()) f *= sheen_terms(m.sheen_layer(k), s.n, transmission_pair(s, wi, wo)).scaling;
  Lobe scratch;
  const CoatTexel coat = level0_coat(m, k, scratch);
  if (coat.present()) f -= (coat_fresnel<double>(coat, wo) * double(base.coat)) * f;
  return f;
}

void accumulate_level0_double(const MaterialTexels& m, std::size_t k, double scale, std::span<glm::dvec3> table) {
  const Lobe base = level0_lobe(m, k);
  Lobe scratch;
  const CoatTexel coat = level0_coat(m, k, scratch);
  if (!m.has_sheen()) {
    accumulate_coated_double({&base, 1}, coat, scale, table);
    return;
  }
  // The lobe's table, scaled and added to pair by pair by the sheen, is the base under the coat.
  static thread_local BrdfTable f, f_coated;
  f.assign(DirectionGrid::kPairs, glm::dvec3(0));
  accumulate_lobe_double(base, 1.0, f);
  apply_sheen(m.sheen_layer(k), glm::normalize(glm::dvec3(base.normal)), f);
  if (!coat.present()) {
    for (std::size_t q = 0; q < f.size(); ++q) table[q] += scale * f[q];
    return;
  }
  f_coated.resize(f.size());
  for (std::size_t q = 0; q < f.size(); ++q) f_coated[q] = double(base.coat) * f[q];
  accumulate_coat<double>({&base, 1}, coat, f, f_coated, scale, table);
}

glm::dvec3 ExactReference::eval(int level, int i, int j, const glm::dvec3& wi, const glm::dvec3& wo) const {
  const Coverage c = coverage(level0(), level, i, j);
  const bool below = wi.z < 0 && wo.z > 0;
  const PairTerms<double> p = pair_terms<double>(wi, wo);
  if (!p.valid && !below) return glm::dvec3(0);
  const glm::dvec3 sum = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<int>(c.rows.begin, c.rows.end), glm::dvec3(0),
      [&](const tbb::blocked_range<int>& r, glm::dvec3 acc) {
        for (int y = r.begin(); y < r.end(); ++y)
          for (int x = c.columns.begin; x < c.columns.end; ++x) {
            const std::size_t k = texels_.index(x, y);
            acc += below ? level0_transmission_eval(texels_, k, wi, wo) : level0_eval(texels_, k, p);
          }
        return acc;
      },
      [](const glm::dvec3& a, const glm::dvec3& b) { return a + b; });
  return sum / static_cast<double>(c.count());
}

BrdfTable ExactReference::table(int level, int i, int j) const {
  const Coverage c = coverage(level0(), level, i, j);
  const double scale = 1.0 / static_cast<double>(c.count());
  auto rows = [&](int y0, int y1, BrdfTable& acc) {
    for (int y = y0; y < y1; ++y)
      for (int x = c.columns.begin; x < c.columns.end; ++x) accumulate_level0_double(texels_, texels_.index(x, y), scale, acc);
  };
  // A texel of a few rows is one task (the callers run many texels in parallel); a coarse texel
  // splits its rows among the threads, each with its own table.
  if (c.rows.size() <= 4) {
    BrdfTable t = make_table();
    rows(c.rows.begin, c.rows.end, t);
    return t;
  }
  return tbb::parallel_deterministic_reduce(
      tbb::blocked_range<int>(c.rows.begin, c.rows.end, 2), BrdfTable{},
      [&](const tbb::blocked_range<int>& r, BrdfTable acc) {
        if (acc.empty()) acc = make_table();
        rows(r.begin(), r.end(), acc);
        return acc;
      },
      [](BrdfTable a, const BrdfTable& b) {
        if (a.empty()) return b;
        if (b.empty()) return a;
        for (std::size_t k = 0; k < a.size(); ++k) a[k] += b[k];
        return a;
      });
}

}  // namespace svbrdf
