#include "appearance/albedo.h"

#include <cmath>

#include "appearance/rng.h"

namespace svbrdf {

Rgb directional_albedo(const Bsdf& bsdf, const glm::vec3& wo, int strata, std::uint64_t seed) {
  // u.x runs through its n strata in order, so the energy split and the lobe choice sweep [0, 1)
  // once; (u.y, u.z) follow the R2 sequence (Roberts 2018: additive recurrence with the plastic
  // number), whose every run of consecutive points is evenly spread, so each lobe's block of
  // samples is stratified too. A random shift (Cranley–Patterson) keeps the estimate unbiased.
  const std::size_t n = static_cast<std::size_t>(strata) * static_cast<std::size_t>(strata);
  Rng rng(seed, 0x61);
  const double plastic = 1.32471795724474602596;
  const double a1 = 1.0 / plastic, a2 = 1.0 / (plastic * plastic);
  const double s1 = rng.next_double(), s2 = rng.next_double(), sx = rng.next_double();
  glm::dvec3 sum(0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double k = static_cast<double>(i);
    const double uy = std::fmod(s1 + k * a1, 1.0), uz = std::fmod(s2 + k * a2, 1.0);
    const SampleU u(static_cast<float>((k + sx) / static_cast<double>(n)), static_cast<float>(uy), static_cast<float>(uz));
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
