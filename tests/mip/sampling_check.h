#pragma once
// The check of a texel mixture's sampler (mip/lobe_mixture_bsdf.h) that the lookup and sheen tests
// share: pdf() is the density sample() draws from (χ² over 64 bins of the hemisphere), every weight is
// f·cosθ/pdf, and their mean is ∫ f·cosθ dωi by quadrature.
//
// The quadrature is adaptive, because a glossy lobe's density is a peak a few α wide about its mirror
// direction (α ≥ 10⁻³, lobe.h) that a fixed grid fine enough for the rest of the hemisphere misses or
// hits by chance. It integrates over w = cosθ and φ, in which dω = dw dφ has no singularity at the
// horizon, on a base grid aligned with the χ² bins; a cell is split in four while its midpoint value
// and its quarters' sum differ by more than kTolerance, or while it is wider than a quarter of a lobe's
// α and lies within kPeakWidths α of that lobe's mirror direction (where the first criterion could be
// fooled by a peak that falls between the midpoints).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "appearance/rng.h"
#include "mip/lobe_mixture_bsdf.h"

namespace svbrdf::testing_sampling {

constexpr double kPi = 3.14159265358979323846;

// A hemisphere quadrature of one mixture at one wo: the pdf's mass and ∫ f·cosθ dωi (green) per cell.
class AdaptiveQuadrature {
 public:
  static constexpr double kTolerance = 1e-9;  // per cell, of a total of at most 1
  static constexpr double kPeakWidths = 8.0;
  static constexpr int kMaxDepth = 16;

  struct Sums {
    double pdf = 0, fcos = 0;
  };

  AdaptiveQuadrature(const LobeMixtureBsdf& bsdf, const glm::vec3& wo) : bsdf_(bsdf), wo_(wo) {
    // Each lobe's mirror direction and its α (the base's lobes and the coat's).
    auto add = [&](const Lobe& l) {
      const glm::dvec3 n = glm::normalize(glm::dvec3(l.normal)), o(wo);
      const glm::dvec3 r = 2.0 * glm::dot(o, n) * n - o;
      if (r.z > 0) peaks_[std::size_t(peak_count_++)] = {glm::normalize(r), std::sqrt(double(l.alpha2))};
    };
    for (int k = 0; k < bsdf.size() && peak_count_ < kMaxPeaks; ++k) add(bsdf.lobe(k));
    for (int k = 0; k < bsdf.coat_size() && peak_count_ < kMaxPeaks; ++k) add(bsdf.coat_lobe(k));
  }

  // The integrals over w ∈ [w0, w1], φ ∈ [p0, p1].
  Sums integrate(double w0, double w1, double p0, double p1) const {
    return refine(w0, w1, p0, p1, midpoint(w0, w1, p0, p1), 0);
  }

 private:
  static constexpr int kMaxPeaks = 2 * kMaxLobes;
  struct Peak {
    glm::dvec3 dir;
    double alpha;
  };

  static glm::dvec3 direction(double w, double p) {
    const double s = std::sqrt(std::max(0.0, 1 - w * w));
    return {s * std::cos(p), s * std::sin(p), w};
  }

  Sums midpoint(double w0, double w1, double p0, double p1) const {
    const glm::vec3 wi(direction(0.5 * (w0 + w1), 0.5 * (p0 + p1)));
    const double area = (w1 - w0) * (p1 - p0);
    return {double(bsdf_.pdf(wi, wo_)) * area, double(bsdf_.eval(wi, wo_).g) * double(wi.z) * area};
  }

  // Whether the cell is wider than a quarter of some lobe's α within kPeakWidths α of its peak.
  bool near_unresolved_peak(double w0, double w1, double p0, double p1) const {
    const glm::dvec3 c = direction(0.5 * (w0 + w1), 0.5 * (p0 + p1));
    double radius = 0;  // the largest angle from the centre to a corner
    for (const double w : {w0, w1})
      for (const double p : {p0, p1})
        radius = std::max(radius, std::acos(std::clamp(glm::dot(c, direction(w, p)), -1.0, 1.0)));
    for (int k = 0; k < peak_count_; ++k) {
      const Peak& pk = peaks_[std::size_t(k)];
      if (radius <= 0.25 * pk.alpha) continue;
      if (std::acos(std::clamp(glm::dot(c, pk.dir), -1.0, 1.0)) < kPeakWidths * pk.alpha + radius) return true;
    }
    return false;
  }

  Sums refine(double w0, double w1, double p0, double p1, const Sums& whole, int depth) const {
    const double wm = 0.5 * (w0 + w1), pm = 0.5 * (p0 + p1);
    const std::array<Sums, 4> q{midpoint(w0, wm, p0, pm), midpoint(wm, w1, p0, pm), midpoint(w0, wm, pm, p1),
                                midpoint(wm, w1, pm, p1)};
    Sums sum;
    for (const Sums& s : q) sum.pdf += s.pdf, sum.fcos += s.fcos;
    const bool converged =
        std::abs(sum.pdf - whole.pdf) <= kTolerance && std::abs(sum.fcos - whole.fcos) <= kTolerance;
    if (depth >= kMaxDepth || (converged && !near_unresolved_peak(w0, w1, p0, p1))) return sum;
    const Sums a = refine(w0, wm, p0, pm, q[0], depth + 1), b = refine(wm, w1, p0, pm, q[1], depth + 1),
               c = refine(w0, wm, pm, p1, q[2], depth + 1), d = refine(wm, w1, pm, p1, q[3], depth + 1);
    return {a.pdf + b.pdf + c.pdf + d.pdf, a.fcos + b.fcos + c.fcos + d.fcos};
  }

  const LobeMixtureBsdf& bsdf_;
  glm::vec3 wo_;
  std::array<Peak, kMaxPeaks> peaks_{};
  int peak_count_ = 0;
};

inline void expect_sampling_matches_pdf_and_integral(const LobeMixtureBsdf& bsdf, const glm::vec3& wo) {
  // Bins: 8 in u = sin²θ (equal cosine-weighted mass) × 8 in φ; each bin's expected mass by the adaptive
  // quadrature over sub × sub base cells (w = √(1 − u) runs down as u runs up).
  constexpr int nb = 8, sub = 16;
  const AdaptiveQuadrature quadrature(bsdf, wo);
  std::array<double, nb * nb> expected{};
  double integral = 0;
  for (int a = 0; a < nb; ++a) {
    const double w_hi = std::sqrt(1.0 - double(a) / nb), w_lo = std::sqrt(1.0 - double(a + 1) / nb);
    for (int b = 0; b < nb; ++b)
      for (int x = 0; x < sub; ++x)
        for (int y = 0; y < sub; ++y) {
          const double w0 = w_lo + (w_hi - w_lo) * x / sub, w1 = w_lo + (w_hi - w_lo) * (x + 1) / sub;
          const double p0 = 2 * kPi * (b + double(y) / sub) / nb, p1 = 2 * kPi * (b + double(y + 1) / sub) / nb;
          const AdaptiveQuadrature::Sums s = quadrature.integrate(w0, w1, p0, p1);
          expected[static_cast<std::size_t>(a * nb + b)] += s.pdf;
          integral += s.fcos;
        }
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
