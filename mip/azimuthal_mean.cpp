#include "mip/azimuthal_mean.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "base/math.h"

namespace svbrdf {

namespace {

// ⟨1/(p + q cos φ)⟩ and ⟨1/(p + q cos φ)²⟩ from lo = p − |q| and hi = p + |q| (both > 0), which the
// caller forms without cancellation (lo is ~α²/2 at a sharp lobe's peak).
double mean_inv1(double lo, double hi) { return 1.0 / std::sqrt(lo * hi); }
double mean_inv2(double lo, double hi) {
  const double pq = lo * hi;
  return 0.5 * (lo + hi) / (pq * std::sqrt(pq));
}
// Their n-th Fourier coefficients ⟨cos nφ/(p + q cos φ)^m⟩. From 1/(p + q cos φ) = (1 + 2 Σ ρⁿ cos nφ)/S,
// S = √(p² − q²), ρ = (S − p)/q (|ρ| < 1; ρ has the sign of −q): ρⁿ/S, and, as −∂/∂p of it
// (∂ρ/∂p = −ρ/S), ρⁿ(nS + p)/S³. |ρ| = (√hi − √lo)/(√hi + √lo), free of cancellation.
double rho_abs(double lo, double hi) {
  const double a = std::sqrt(lo), b = std::sqrt(hi);
  return (b - a) / (b + a);
}
double harmonic_inv1(double lo, double hi, double rho_n) { return rho_n / std::sqrt(lo * hi); }
double harmonic_inv2(double lo, double hi, double rho_n, int n) {
  const double pq = lo * hi, S = std::sqrt(pq);
  return rho_n * (n * S + 0.5 * (lo + hi)) / (pq * S);
}

// ⟨cos nφ/(1 − k c²)⟩ and ⟨cos nφ/(1 − k c²)²⟩ for 0 ≤ k < 1 and n < count (φ about the lobe's azimuth),
// from 1/(1 − k c²) = ½[1/(1 − s c) + 1/(1 + s c)], s = √k; cm = cos(θ − δ) = A + B and cp = cos(θ + δ) = A − B.
struct Means {
  double inv1[3], inv2[3];
};
Means ggx_means(double k, double cm, double cp, int count) {
  const double s = std::sqrt(k);
  // 1 − s c: p = 1 − sA, |q| = sB, so p − |q| = 1 − s·cm and p + |q| = 1 − s·cp; 1 + s c: 1 + s·cp, 1 + s·cm.
  const double a_lo = 1 - s * cm, a_hi = 1 - s * cp, b_lo = 1 + s * cp, b_hi = 1 + s * cm;
  Means m{};
  double m1a = mean_inv1(a_lo, a_hi), m1b = mean_inv1(b_lo, b_hi);
  double m2a = mean_inv2(a_lo, a_hi), m2b = mean_inv2(b_lo, b_hi);
  // 1/(1 − k c²)² = ¼[1/(1 − sc)² + 1/(1 + sc)² + 1/(1 − sc) + 1/(1 + sc)]
  m.inv1[0] = 0.5 * (m1a + m1b), m.inv2[0] = 0.25 * (m2a + m2b + m1a + m1b);
  // q = −sB ≤ 0 in 1 − s c (ρ > 0), q = sB ≥ 0 in 1 + s c (ρ < 0).
  const double rho_a = rho_abs(a_lo, a_hi), rho_b = -rho_abs(b_lo, b_hi);
  double ra = 1, rb = 1;
  for (int n = 1; n < count; ++n) {
    ra *= rho_a, rb *= rho_b;
    m1a = harmonic_inv1(a_lo, a_hi, ra), m1b = harmonic_inv1(b_lo, b_hi, rb);
    m2a = harmonic_inv2(a_lo, a_hi, ra, n), m2b = harmonic_inv2(b_lo, b_hi, rb, n);
    m.inv1[n] = 0.5 * (m1a + m1b), m.inv2[n] = 0.25 * (m2a + m2b + m1a + m1b);
  }
  return m;
}

// D as lobe_d has it, from c = n̂·h alone (|n̂×h|² = 1 − c²).
double d_of_c(const LobeShape<double>& s, double c) {
  return lobe_d(s, c, glm::dvec3(std::sqrt(std::max(0.0, 1.0 - c * c)), 0.0, 0.0));
}

// out[n] = ⟨D cos nψ⟩ for n < count (≤ 3).
void fourier_d(const LobeShape<double>& s, double theta, int count, double* out) {
  for (int n = 0; n < count; ++n) out[n] = 0.0;
  if (!s.valid) return;
  const double cd = std::clamp(s.n.z, -1.0, 1.0), sd = std::sqrt(std::max(0.0, 1.0 - cd * cd));
  const double A = std::cos(theta) * cd, B = std::sin(theta) * sd;
  const double cm = A + B, cp = A - B;  // cos(θ ∓ δ)
  if (!(cp > 1e-3) || std::max(s.alpha2, s.alpha2_hi) >= 1.0) {
    constexpr int kPoints = 1024;  // over [0, π]: the integrand is even in φ
    for (int i = 0; i < kPoints; ++i) {
      const double phi = kPiD * (i + 0.5) / kPoints, d = d_of_c(s, A + B * std::cos(phi));
      for (int n = 0; n < count; ++n) out[n] += d * (n == 0 ? 1.0 : std::cos(n * phi)) / kPoints;
    }
    return;
  }
  if (s.alpha2_hi > 0) {
    const double l = s.alpha2, h = s.alpha2_hi;
    const Means ml = ggx_means(1 - l, cm, cp, count), mh = ggx_means(1 - h, cm, cp, count);
    // The band: 1/((1 − k_l x)(1 − k_h x)) = [k_l/(1 − k_l x) − k_h/(1 − k_h x)]/(k_l − k_h), x = c².
    for (int n = 0; n < count; ++n) {
      const double upper = s.two_point ? h * mh.inv2[n] : s.lmean * ((1 - l) * ml.inv1[n] - (1 - h) * mh.inv1[n]) / (h - l);
      out[n] = (s.ggx * upper + (1 - s.ggx) * l * ml.inv2[n]) / kPiD;
    }
    return;
  }
  const Means m = ggx_means(1 - s.alpha2, cm, cp, count);
  for (int n = 0; n < count; ++n) out[n] = s.ggx * s.alpha2 * m.inv2[n] / kPiD;
  if (s.ggx < 1) {
    const double b2 = s.alpha2 * s.skirt, cmin = 1.0 / std::sqrt(1.0 + 60.0 * b2);
    if (cm > cmin) {
      const double phi_max = B > 0 ? std::acos(std::clamp((cmin - A) / B, -1.0, 1.0)) : kPiD;
      constexpr int kPoints = 48;
      const double scale = (1 - s.ggx) / kPoints * (phi_max / kPiD) / kPiD;
      for (int i = 0; i < kPoints; ++i) {
        const double phi = phi_max * (i + 0.5) / kPoints, c = A + B * std::cos(phi);
        if (!(c > 0)) continue;
        const double c2 = c * c, x = (1 - c2) / (c2 * b2);
        if (!(x < 60)) continue;
        const double d = std::exp(-x) / (b2 * c2 * c2) * scale;
        for (int n = 0; n < count; ++n) out[n] += d * (n == 0 ? 1.0 : std::cos(n * phi));
      }
    }
  }
}

}  // namespace

double azimuthal_mean_d(const LobeShape<double>& s, double theta) {
  double m;
  fourier_d(s, theta, 1, &m);
  return m;
}

std::array<double, 3> azimuthal_fourier_d(const LobeShape<double>& s, double theta) {
  std::array<double, 3> out;
  fourier_d(s, theta, 3, out.data());
  return out;
}

}  // namespace svbrdf
