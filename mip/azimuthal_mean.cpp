#include "mip/azimuthal_mean.h"

#include <algorithm>
#include <cmath>

namespace svbrdf {

namespace {

constexpr double kPi = 3.14159265358979323846;

// ⟨1/(p + q cos φ)⟩ and ⟨1/(p + q cos φ)²⟩ from lo = p − |q| and hi = p + |q| (both > 0), which the
// caller forms without cancellation (lo is ~α²/2 at a sharp lobe's peak).
double mean_inv1(double lo, double hi) { return 1.0 / std::sqrt(lo * hi); }
double mean_inv2(double lo, double hi) {
  const double pq = lo * hi;
  return 0.5 * (lo + hi) / (pq * std::sqrt(pq));
}

// ⟨1/(1 − k c²)⟩ and ⟨1/(1 − k c²)²⟩ for 0 ≤ k < 1, from 1/(1 − k c²) = ½[1/(1 − s c) + 1/(1 + s c)],
// s = √k; cm = cos(θ − δ) = A + B and cp = cos(θ + δ) = A − B.
struct Means {
  double inv1, inv2;
};
Means ggx_means(double k, double cm, double cp) {
  const double s = std::sqrt(k);
  // 1 − s c: p = 1 − sA, |q| = sB, so p − |q| = 1 − s·cm and p + |q| = 1 − s·cp; 1 + s c: 1 + s·cp, 1 + s·cm.
  const double a_lo = 1 - s * cm, a_hi = 1 - s * cp, b_lo = 1 + s * cp, b_hi = 1 + s * cm;
  const double m1a = mean_inv1(a_lo, a_hi), m1b = mean_inv1(b_lo, b_hi);
  const double m2a = mean_inv2(a_lo, a_hi), m2b = mean_inv2(b_lo, b_hi);
  // 1/(1 − k c²)² = ¼[1/(1 − sc)² + 1/(1 + sc)² + 1/(1 − sc) + 1/(1 + sc)]
  return {0.5 * (m1a + m1b), 0.25 * (m2a + m2b + m1a + m1b)};
}

// D as lobe_d has it, from c = n̂·h alone (|n̂×h|² = 1 − c²).
double d_of_c(const LobeShape<double>& s, double c) {
  return lobe_d(s, c, glm::dvec3(std::sqrt(std::max(0.0, 1.0 - c * c)), 0.0, 0.0));
}

}  // namespace

double azimuthal_mean_d(const LobeShape<double>& s, double theta) {
  if (!s.valid) return 0.0;
  const double cd = std::clamp(s.n.z, -1.0, 1.0), sd = std::sqrt(std::max(0.0, 1.0 - cd * cd));
  const double A = std::cos(theta) * cd, B = std::sin(theta) * sd;
  const double cm = std::cos(theta - std::acos(cd)), cp = A - B;
  if (!(cp > 1e-3) || std::max(s.alpha2, s.alpha2_hi) >= 1.0) {
    constexpr int kPoints = 1024;  // over [0, π]: the integrand is even in φ
    double sum = 0;
    for (int i = 0; i < kPoints; ++i) sum += d_of_c(s, A + B * std::cos(kPi * (i + 0.5) / kPoints));
    return sum / kPoints;
  }
  if (s.alpha2_hi > 0) {
    const double l = s.alpha2, h = s.alpha2_hi;
    const Means ml = ggx_means(1 - l, cm, cp), mh = ggx_means(1 - h, cm, cp);
    // The band: 1/((1 − k_l x)(1 − k_h x)) = [k_l/(1 − k_l x) − k_h/(1 − k_h x)]/(k_l − k_h), x = c².
    const double upper = s.two_point ? h * mh.inv2 : s.lmean * ((1 - l) * ml.inv1 - (1 - h) * mh.inv1) / (h - l);
    return (s.ggx * upper + (1 - s.ggx) * l * ml.inv2) / kPi;
  }
  double d = s.ggx * s.alpha2 * ggx_means(1 - s.alpha2, cm, cp).inv2 / kPi;
  if (s.ggx < 1) {
    const double b2 = s.alpha2 * s.skirt, cmin = 1.0 / std::sqrt(1.0 + 60.0 * b2);
    if (cm > cmin) {
      const double phi_max = B > 0 ? std::acos(std::clamp((cmin - A) / B, -1.0, 1.0)) : kPi;
      constexpr int kPoints = 48;
      double sum = 0;
      for (int i = 0; i < kPoints; ++i) {
        const double c = A + B * std::cos(phi_max * (i + 0.5) / kPoints);
        if (!(c > 0)) continue;
        const double c2 = c * c, x = (1 - c2) / (c2 * b2);
        if (x < 60) sum += std::exp(-x) / (b2 * c2 * c2);
      }
      d += (1 - s.ggx) * sum / kPoints * (phi_max / kPi) / kPi;
    }
  }
  return d;
}

}  // namespace svbrdf
