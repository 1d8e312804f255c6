#include "appearance/albedo.h"

#include <cmath>
#include <numeric>
#include <vector>

#include "appearance/rng.h"

namespace svbrdf {

Rgb directional_albedo(const Bsdf& bsdf, const glm::vec3& wo, int strata, std::uint64_t seed) {
  const std::size_t n = static_cast<std::size_t>(strata) * static_cast<std::size_t>(strata);
  Rng rng(seed, 0x61);
  // A random permutation for u.x so that each sample's u.x falls in its own 1/n slice.
  std::vector<std::uint32_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0u);
  for (std::size_t i = n; i > 1; --i) std::swap(perm[i - 1], perm[rng.next_u32() % i]);
  glm::dvec3 sum(0.0);
  std::size_t i = 0;
  for (int a = 0; a < strata; ++a)
    for (int b = 0; b < strata; ++b, ++i) {
      const SampleU u((static_cast<float>(perm[i]) + rng.next_float()) / static_cast<float>(n),
                      (static_cast<float>(a) + rng.next_float()) / static_cast<float>(strata),
                      (static_cast<float>(b) + rng.next_float()) / static_cast<float>(strata));
      const BsdfSample s = bsdf.sample(wo, glm::min(u, SampleU(0x1.fffffep-1f)));
      if (s.kind != SampleKind::finite) continue;
      const float p = bsdf.pdf(s.wi, wo);
      if (p > 0) sum += glm::dvec3(bsdf.eval(s.wi, wo)) * (std::abs(static_cast<double>(s.wi.z)) / p);
    }
  return Rgb(sum / static_cast<double>(n));
}

Rgb impulse_total(const Bsdf& bsdf, const glm::vec3& wo) {
  const Impulses imp = bsdf.impulses_in(wo);
  Rgb total(0);
  for (int k = 0; k < imp.count; ++k) total += imp.items[static_cast<std::size_t>(k)].magnitude;
  return total;
}

}  // namespace svbrdf
