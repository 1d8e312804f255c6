#pragma once
// Private to mip/: included by mip's .cpp files only (lobe_reduction.h is the reduction's public face).
// The numerical tools of the lobe reduction: 1 − e^(−x) without cancellation, the scaled Bessel
// function I0, Gauss–Legendre rules, a bracketing root finder (regula falsi with the Illinois rule)
// and the inverse of sinh(u)/u.
#include <array>
#include <cmath>
#include <cstddef>

#include <glm/glm.hpp>

#include "base/math.h"
#include "base/series_log.h"

namespace svbrdf::reduction {

// The mean of three channels (ρ or F0 of a lobe, as the cost model and the albedo see them).
inline double mean3(const glm::vec3& c) { return (double(c.x) + c.y + c.z) / 3.0; }

// 1 − e^(−x) for x ≥ 0 within 4e-7 (series_exp; the series near 0, where the difference would cancel):
// the cone masses of lobe_fit.cpp run it for every candidate merge that makes a narrow spread core.
inline double one_minus_exp(double x) {
  return x < 1e-2 ? x * (1.0 - x * (0.5 - x / 6.0)) : 1.0 - double(series_exp(static_cast<float>(-x)));
}

// e^(−x)·I0(x) for x ≥ 0 (I0 the modified Bessel function of order 0), within 2e-7 relative:
// Abramowitz & Stegun 9.8.1 (x ≤ 3.75) and 9.8.2 (above).
double scaled_bessel_i0(double x);

// Gauss–Legendre nodes and weights on [0, 1], by Newton's method on the Legendre polynomial.
template <int N>
struct GaussLegendre {
  std::array<double, N> x{}, w{};
  GaussLegendre() {
    for (int i = 0; i < N; ++i) {
      double z = std::cos(kPiD * (i + 0.75) / (N + 0.5)), dp = 1.0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1.0, p1 = z;  // P_0, P_1, then up to P_N by the three-term recurrence
        for (int k = 2; k <= N; ++k) {
          const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1, p1 = p2;
        }
        dp = N * (z * p1 - p0) / (z * z - 1.0);
        const double step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-15) break;
      }
      x[static_cast<std::size_t>(i)] = 0.5 * (1.0 - z);
      w[static_cast<std::size_t>(i)] = 1.0 / ((1.0 - z * z) * dp * dp);  // 2/((1 − z²)P'²), halved for [0, 1]
    }
  }
};

// Finds where f (continuous) crosses 0 on [lo, hi], given f_lo = f(lo) and f_hi = f(hi) (of opposite
// signs; else the end nearer 0): `bisections` halvings first (where f is flat at the ends, as a sigmoid
// is), then regula falsi with the Illinois rule (halve the value kept at an end that stays twice), to
// |f| < tol or max_steps steps in all (Dowell & Jarratt 1971, "A modified regula falsi method for
// computing the root of an equation", BIT 11).
template <class F>
double illinois_root(F&& f, double lo, double f_lo, double hi, double f_hi, double tol, int bisections = 0,
                     int max_steps = 40) {
  if (!(f_lo * f_hi < 0)) return std::abs(f_lo) <= std::abs(f_hi) ? lo : hi;
  double t = lo;
  int kept = 0;  // +1: lo moved last, −1: hi moved last
  for (int it = 0; it < max_steps; ++it) {
    const bool falsi = it >= bisections;
    t = falsi ? (lo * f_hi - hi * f_lo) / (f_hi - f_lo) : 0.5 * (lo + hi);
    const double v = f(t);
    if (std::abs(v) < tol) break;
    if ((v < 0) == (f_lo < 0)) {
      lo = t, f_lo = v;
      if (falsi && kept == 1) f_hi *= 0.5;
      kept = 1;
    } else {
      hi = t, f_hi = v;
      if (falsi && kept == -1) f_lo *= 0.5;
      kept = -1;
    }
  }
  return t;
}

// The inverse of sinh(u)/u = T (T ≥ 1) to ~1e-5, for a Newton iteration to start from (one step then
// reaches 1e-10; band_span, lobe_fit.cpp): tabulated over w = ln(1 + √(T − 1)), in which u is smooth
// (u ≈ √(6(T − 1)) near T = 1, ≈ ln(2T·ln 2T) far out), by bisection once.
class SinhcInverse {
 public:
  static const SinhcInverse& get();
  double guess(double target) const;

 private:
  static constexpr int kSize = 1024;
  static constexpr double kMaxW = 4.0;  // T up to 1 + (e⁴ − 1)² ≈ 2900
  SinhcInverse();
  std::array<double, kSize> u_{};
};

}  // namespace svbrdf::reduction
