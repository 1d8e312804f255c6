#pragma once
// The check of a texel mixture's sampler (mip/lobe_mixture_bsdf.h) that the lookup and sheen tests
// share: pdf() is the density sample() draws from (χ² over 64 bins of the hemisphere), every weight is
// f·cosθ/pdf, and their mean is ∫ f·cosθ dωi by dense quadrature.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "appearance/rng.h"
#include "mip/lobe_mixture_bsdf.h"

namespace svbrdf::testing_sampling {

inline void expect_sampling_matches_pdf_and_integral(const LobeMixtureBsdf& bsdf, const glm::vec3& wo) {
  constexpr double kPi = 3.14159265358979323846;
  // Bins: 8 in cos²θ (equal cosine-weighted mass) × 8 in φ; expected mass by midpoint quadrature.
  constexpr int nb = 8, sub = 48;
  std::array<double, nb * nb> expected{};
  double integral = 0;
  for (int a = 0; a < nb * sub; ++a)
    for (int b = 0; b < nb * sub; ++b) {
      const double u = (a + 0.5) / (nb * sub), v = (b + 0.5) / (nb * sub);
      const double ct = std::sqrt(1 - u), st = std::sqrt(u), phi = 2 * kPi * v;
      const glm::vec3 wi(float(st * std::cos(phi)), float(st * std::sin(phi)), float(ct));
      const double dw = kPi / ((nb * sub) * (nb * sub)) / ct;  // solid angle of the cell (dω = π du dv / cosθ)
      expected[static_cast<std::size_t>((a / sub) * nb + b / sub)] += bsdf.pdf(wi, wo) * dw;
      integral += double(bsdf.eval(wi, wo).g) * ct * dw;
    }
  Rng rng(23, 5);
  constexpr int n = 200000;
  std::array<double, nb * nb> observed{};
  double weight_sum = 0;
  int absorbed = 0;
  for (int s = 0; s < n; ++s) {
    const BsdfSample smp = bsdf.sample(wo, {rng.next_float(), rng.next_float(), rng.next_float()});
    if (smp.kind != SampleKind::finite) {
      ++absorbed;
      continue;
    }
    ASSERT_GT(smp.wi.z, 0.0f);
    EXPECT_NEAR(smp.pdf, bsdf.pdf(smp.wi, wo), 1e-4f * smp.pdf);
    const glm::vec3 f = bsdf.eval(smp.wi, wo);
    EXPECT_NEAR(smp.weight.g, f.g * smp.wi.z / smp.pdf, 1e-4f * (smp.weight.g + 1e-6f));
    weight_sum += smp.weight.g;
    const double u = 1 - double(smp.wi.z) * smp.wi.z;
    const double v = std::fmod(std::atan2(double(smp.wi.y), double(smp.wi.x)) / (2 * kPi) + 1.0, 1.0);
    const int a = std::min(nb - 1, static_cast<int>(u * nb)), b = std::min(nb - 1, static_cast<int>(v * nb));
    observed[static_cast<std::size_t>(a * nb + b)] += 1;
  }
  double chi2 = 0, mass = 0;
  for (int k = 0; k < nb * nb; ++k) {
    const double e = expected[static_cast<std::size_t>(k)] * n;
    mass += expected[static_cast<std::size_t>(k)];
    if (e > 5) chi2 += std::pow(observed[static_cast<std::size_t>(k)] - e, 2) / e;
  }
  EXPECT_LT(chi2, 120.0);  // 63 degrees of freedom: p ≈ 1e-5
  EXPECT_NEAR(mass + double(absorbed) / n, 1.0, 0.01);  // what is not above the horizon was absorbed
  EXPECT_NEAR(weight_sum / n, integral, 0.02 * integral);
  EXPECT_LE(integral, 1.0);  // no texel reflects more than it receives
}

}  // namespace svbrdf::testing_sampling
