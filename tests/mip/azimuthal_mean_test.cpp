// azimuthal_mean_d and azimuthal_fourier_d against brute-force means over azimuth of lobe_d at real
// half vectors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "mip/azimuthal_mean.h"

namespace svbrdf {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;

Lobe tilted(double tilt_deg, double azimuth_deg = 30.0) {
  Lobe l;
  l.weight = 1.0f;
  const double t = tilt_deg * kDeg, a = azimuth_deg * kDeg;
  l.normal = glm::vec3(glm::dvec3(std::sin(t) * std::cos(a), std::sin(t) * std::sin(a), std::cos(t)));
  return l;
}

// The mean of lobe_d over n azimuths of h at polar angle θ about z (the midpoint rule, which is
// spectrally accurate for a smooth periodic integrand once the points resolve the lobe).
// With harmonic n > 0, the mean of lobe_d·cos n(φ − φ₀), φ₀ the lobe's own azimuth.
double brute_force(const LobeShape<double>& s, double theta, int n = 40000, int harmonic = 0) {
  const double phi0 = std::atan2(s.n.y, s.n.x);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * kPi * (i + 0.5) / n;
    const glm::dvec3 h(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    const double c = glm::dot(s.n, h);
    if (c > 0) sum += lobe_d(s, c, glm::cross(s.n, h)) * std::cos(harmonic * (phi - phi0));
  }
  return sum / n;
}

struct Kind {
  std::string name;
  Lobe lobe;
  double tolerance;  // relative: closed forms to rounding, the quadratures to their own error
};

std::vector<Kind> kinds(double tilt_deg) {
  std::vector<Kind> out;
  for (double alpha : {0.001, 0.03, 0.5}) {
    Lobe l = tilted(tilt_deg);
    l.alpha2 = static_cast<float>(alpha * alpha);
    out.push_back({"GGX a=" + std::to_string(alpha), l, 1e-7});
  }
  Lobe band = tilted(tilt_deg);
  band.alpha2 = 1e-4f, band.alpha2_hi = 4e-2f, band.ggx = 0.6f, band.skirt = 1.0f;
  out.push_back({"band with atom", band, 1e-7});
  Lobe two = band;
  two.skirt = 0.0f;
  out.push_back({"two-point", two, 1e-7});
  Lobe core = tilted(tilt_deg);
  core.alpha2 = 4e-4f, core.ggx = 0.4f, core.skirt = 6.0f;
  out.push_back({"spread core", core, 1e-4});
  return out;
}

TEST(AzimuthalMean, MatchesTheMeanOverAzimuthOfEveryLobeKind) {
  for (double tilt : {0.0, 1.0, 5.0, 20.0})
    for (const Kind& k : kinds(tilt)) {
      const LobeShape<double> s = lobe_shape<double>(k.lobe, false);
      ASSERT_TRUE(s.valid);
      for (double theta_deg : {0.0, 0.5, 1.0, 4.0, 5.0, 12.0, 30.0, 60.0, 75.0}) {
        const double theta = theta_deg * kDeg;
        const double want = brute_force(s, theta), got = azimuthal_mean_d(s, theta);
        // Relative to the value, or to a millionth of the peak far out in the tail.
        const double scale = std::max(want, 1e-6 * lobe_d(s, 1.0, glm::dvec3(0)));
        // Where the circle reaches the lobe's horizon the quadrature fallback answers.
        const double tol = theta_deg + tilt >= 89.0 ? 1e-3 : k.tolerance;
        EXPECT_NEAR(got, want, tol * scale) << k.name << ", tilt " << tilt << "°, θ " << theta_deg << "°";
      }
    }
}

TEST(AzimuthalMean, HarmonicsMatchTheFourierCoefficientsOverAzimuthOfEveryLobeKind) {
  for (double tilt : {1.0, 5.0, 20.0})
    for (const Kind& k : kinds(tilt)) {
      const LobeShape<double> s = lobe_shape<double>(k.lobe, false);
      for (int n : {1, 2})
        for (double theta_deg : {0.5, 1.0, 4.0, 5.0, 12.0, 30.0, 60.0}) {
          const double theta = theta_deg * kDeg;
          const double want = brute_force(s, theta, 40000, n), got = azimuthal_fourier_d(s, theta)[static_cast<std::size_t>(n)];
          // Relative to the mean (a coefficient is at most it), or a millionth of the peak far out.
          const double scale = std::max(brute_force(s, theta), 1e-6 * lobe_d(s, 1.0, glm::dvec3(0)));
          const double tol = theta_deg + tilt >= 89.0 ? 1e-3 : k.tolerance;
          EXPECT_NEAR(got, want, tol * scale) << k.name << ", n " << n << ", tilt " << tilt << "°, θ " << theta_deg << "°";
        }
    }
}

TEST(AzimuthalMean, AnUntiltedLobeIsItsOwnProfile) {
  for (const Kind& k : kinds(0.0)) {
    const LobeShape<double> s = lobe_shape<double>(k.lobe, false);
    for (double theta_deg : {0.0, 0.2, 3.0, 45.0}) {
      const double theta = theta_deg * kDeg;
      const double d = lobe_d(s, std::cos(theta), glm::dvec3(std::sin(theta), 0.0, 0.0));
      EXPECT_NEAR(azimuthal_mean_d(s, theta), d, 1e-9 * d) << k.name << ", θ " << theta_deg << "°";
    }
  }
}

TEST(AzimuthalMean, RoughBandsBeyondAlphaOneFallBackToQuadrature) {
  Lobe l = tilted(3.0);
  l.alpha2 = 0.05f, l.alpha2_hi = 1.2f, l.ggx = 1.0f, l.skirt = 1.0f;  // k_h < 0: no real factors
  const LobeShape<double> s = lobe_shape<double>(l, false);
  for (double theta_deg : {0.0, 10.0, 40.0}) {
    const double theta = theta_deg * kDeg, want = brute_force(s, theta);
    EXPECT_TRUE(std::isfinite(azimuthal_mean_d(s, theta)));
    EXPECT_NEAR(azimuthal_mean_d(s, theta), want, 1e-6 * want) << "θ " << theta_deg << "°";
  }
}

TEST(AzimuthalMean, AnInvalidLobeHasNone) {
  Lobe l;
  l.weight = 0.0f;
  EXPECT_EQ(azimuthal_mean_d(lobe_shape<double>(l, false), 0.1), 0.0);
}

}  // namespace
}  // namespace svbrdf
