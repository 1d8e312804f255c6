#include "mip/exact_reference.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace svbrdf {

glm::dvec3 ExactReference::eval(int level, int i, int j, const glm::dvec3& wi, const glm::dvec3& wo) const {
  const Coverage c = coverage(level0(), level, i, j);
  const PairTerms<double> p = pair_terms<double>(wi, wo);
  if (!p.valid) return glm::dvec3(0);
  const glm::dvec3 sum = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<int>(c.rows.begin, c.rows.end), glm::dvec3(0),
      [&](const tbb::blocked_range<int>& r, glm::dvec3 acc) {
        for (int y = r.begin(); y < r.end(); ++y)
          for (int x = c.columns.begin; x < c.columns.end; ++x) {
            const std::size_t k = texels_.index(x, y);
            Lobe scratch;
            const Lobe base = level0_lobe(texels_, k);
            const glm::dvec3 f = lobe_eval<double>(base, p);
            acc += coated_eval(f, double(base.coat) * f, {&base, 1}, level0_coat(texels_, k, scratch), p);
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
      for (int x = c.columns.begin; x < c.columns.end; ++x) {
        const std::size_t k = texels_.index(x, y);
        const Lobe base = level0_lobe(texels_, k);
        Lobe scratch;
        accumulate_coated_double({&base, 1}, level0_coat(texels_, k, scratch), scale, acc);
      }
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
