// Fresnel numbers of the issue: water at normal incidence, Brewster's angle, total internal
// reflection, and Schlick against exact over θi, with the exact curve re-derived here from the
// angle form of the Fresnel equations (r_s = −sin(θi−θt)/sin(θi+θt), r_p = tan(θi−θt)/tan(θi+θt)).
#include <gtest/gtest.h>

#include <cmath>
#include <complex>

#include "appearance/fresnel.h"
#include "apps/fresnel_plot.h"

namespace svbrdf {
namespace {

constexpr double kPiD = 3.14159265358979323846;

double exact_angle_form(double theta_i, double n) {
  if (theta_i == 0) return std::pow((n - 1) / (n + 1), 2);
  const double s = std::sin(theta_i) / n;
  if (s >= 1) return 1;
  const double tt = std::asin(s);
  const double rs = std::sin(theta_i - tt) / std::sin(theta_i + tt), rp = std::tan(theta_i - tt) / std::tan(theta_i + tt);
  return 0.5 * (rs * rs + rp * rp);
}

TEST(Fresnel, WaterAtNormalIncidence) {
  EXPECT_NEAR(fresnel_dielectric(1.0f, 1.33f), 0.0201, 1e-4);
  EXPECT_NEAR(fresnel_f0(1.33f), 0.0201, 1e-4);
}

TEST(Fresnel, BrewsterAngleZeroesRp) {
  const double brewster = std::atan(1.5);  // tan θB = n
  const FresnelPolarized at = fresnel_dielectric_polarized(static_cast<float>(std::cos(brewster)), 1.5f);
  EXPECT_LT(at.rp, 1e-7);
  EXPECT_GT(at.rs, 0.1);
  const FresnelPolarized off = fresnel_dielectric_polarized(static_cast<float>(std::cos(brewster - 0.2)), 1.5f);
  EXPECT_GT(off.rp, 1e-3) << "only at Brewster's angle";
}

TEST(Fresnel, TotalInternalReflectionGlassToAir) {
  const double critical = std::asin(1 / 1.5);
  EXPECT_EQ(fresnel_dielectric(static_cast<float>(std::cos(critical + 0.01)), 1 / 1.5f), 1.0f);
  EXPECT_EQ(fresnel_dielectric(static_cast<float>(std::cos(critical + 0.5)), 1 / 1.5f), 1.0f);
  EXPECT_LT(fresnel_dielectric(static_cast<float>(std::cos(critical - 0.01)), 1 / 1.5f), 1.0f);
  // Below the critical angle the inside reflectance equals the outside one at the refracted angle.
  const double ti = 0.5, tt = std::asin(std::sin(ti) / 1.5);
  EXPECT_NEAR(fresnel_dielectric(static_cast<float>(std::cos(tt)), 1 / 1.5f),
              fresnel_dielectric(static_cast<float>(std::cos(ti)), 1.5f), 1e-6);
}

// The conductor reflectance straight from the complex Fresnel equations (Snell with a complex
// index, principal square root), in double.
FresnelPolarized conductor_complex(double cos_i, double eta, double k) {
  using C = std::complex<double>;
  const C n(eta, k);
  const C cos_t = std::sqrt(1.0 - (1.0 - cos_i * cos_i) / (n * n));
  const C rs = (cos_i - n * cos_t) / (cos_i + n * cos_t), rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
  return {static_cast<float>(std::norm(rs)), static_cast<float>(std::norm(rp))};
}

TEST(Fresnel, ConductorMatchesTheComplexEquations) {
  for (const auto& [eta, k] : {std::pair{0.2, 3.9}, std::pair{0.92, 2.45}, std::pair{1.1, 2.14}, std::pair{2.9, 3.0},
                               std::pair{1.5, 0.0}, std::pair{0.05, 0.5}, std::pair{3.0, 0.01}})
    for (int i = 0; i <= 90; ++i) {
      const double c = std::cos(i * kPiD / 180);
      const FresnelPolarized ref = conductor_complex(c, eta, k);
      const FresnelPolarized got = fresnel_conductor_polarized(static_cast<float>(c), static_cast<float>(eta), static_cast<float>(k));
      EXPECT_NEAR(got.rs, ref.rs, 1e-5) << eta << " " << k << " " << i;
      EXPECT_NEAR(got.rp, ref.rp, 1e-5) << eta << " " << k << " " << i;
    }
}

TEST(Fresnel, ExactMatchesTheAngleForm) {
  for (double n : {1.2, 1.33, 1.5, 2.2, 1 / 1.5})
    for (int i = 0; i <= 900; ++i) {
      const double t = i * 0.1 * kPiD / 180;
      EXPECT_NEAR(fresnel_dielectric(static_cast<float>(std::cos(t)), static_cast<float>(n)), exact_angle_form(t, n), 2e-5)
          << "n " << n << " θ " << i * 0.1;
    }
  // A conductor with κ = 0 is a dielectric; at normal incidence R = ((η−1)² + κ²)/((η+1)² + κ²).
  EXPECT_NEAR(fresnel_conductor(0.6f, 1.5f, 0.0f), fresnel_dielectric(0.6f, 1.5f), 1e-6);
  EXPECT_NEAR(fresnel_conductor(1.0f, 0.2f, 3.9f), (0.64 + 15.21) / (1.44 + 15.21), 1e-6);
  EXPECT_NEAR(fresnel_conductor(0.0f, 0.2f, 3.9f), 1.0, 1e-6) << "grazing reflects everything";
}

// Schlick against exact for ior 1.2, 1.5, 2.2 (CGPP Exercise 27.5): the largest difference, found
// here by a dense scan of the angle form, lies at 83–85° (the "about 0.11, 0.036, 0.058").
TEST(Fresnel, SchlickAgainstExactMaxima) {
  struct Case {
    double n, max_diff, at_deg;
  };
  // Pinned from the independent scan below (step 0.001°): 1.2 → 0.11304 at 82.96°, 1.5 → 0.035693
  // at 84.97°, 2.2 → 0.058168 at 84.83°.
  for (const Case c : {Case{1.2, 0.11304, 82.96}, Case{1.5, 0.035693, 84.97}, Case{2.2, 0.058168, 84.83}}) {
    const double f0 = std::pow((c.n - 1) / (c.n + 1), 2);
    double best = 0, best_at = 0;
    for (int i = 0; i < 90000; ++i) {
      const double deg = i * 0.001, t = deg * kPiD / 180;
      const double d = std::abs(exact_angle_form(t, c.n) - (f0 + (1 - f0) * std::pow(1 - std::cos(t), 5)));
      if (d > best) best = d, best_at = deg;
    }
    EXPECT_NEAR(best, c.max_diff, 2e-5) << "n " << c.n;
    EXPECT_NEAR(best_at, c.at_deg, 0.02) << "n " << c.n;
    EXPECT_GT(best_at, 80.0);
    EXPECT_LT(best_at, 85.0);
    // The library's curves (what `svbrdf-brdf fresnel` plots) find the same maximum.
    const FresnelCurves curves = fresnel_curves_dielectric(static_cast<float>(c.n));
    EXPECT_NEAR(curves.max_difference[0], best, 2e-4) << "n " << c.n;
    EXPECT_NEAR(curves.max_at_deg[0], best_at, 0.05) << "n " << c.n;
    // Schlick is exact at normal incidence.
    EXPECT_FLOAT_EQ(fresnel_schlick(static_cast<float>(f0), 1.0f), static_cast<float>(f0));
    EXPECT_NEAR(fresnel_dielectric(1.0f, static_cast<float>(c.n)), f0, 1e-7);
    EXPECT_FLOAT_EQ(fresnel_schlick(static_cast<float>(f0), 0.0f), 1.0f);
  }
}

// Every text of the Fresnel plot lies inside its frame as the PNG draws it (DejaVu Sans through
// OpenImageIO): a conductor's heading, with its material and a summary per channel at four significant
// digits (the widest numbers plot_number writes), once ran past the right edge.
TEST(FresnelPlot, EveryTextFitsTheFrame) {
  for (const FresnelCurves& c : {fresnel_curves_dielectric(1.333f, 91),
                                 fresnel_curves_conductor({0.1568f, 0.4243f, 1.382f}, {3.602f, 2.472f, 1.916f}, 91)}) {
    const Figure fig = fresnel_plot(c);
    int texts = 0;
    for (const Figure::Shape& s : fig.shapes()) {
      if (s.kind != Figure::Shape::Kind::text) continue;
      ++texts;
      const auto [lo, hi] = Figure::text_box(s);
      EXPECT_GT(hi.x - lo.x, 0.0) << s.text;
      EXPECT_GE(lo.x, 0.0) << s.text;
      EXPECT_GE(lo.y, 0.0) << s.text;
      EXPECT_LE(hi.x, fig.width()) << s.text;
      EXPECT_LE(hi.y, fig.height()) << s.text;
    }
    EXPECT_GT(texts, 20) << c.label;
  }
}

}  // namespace
}  // namespace svbrdf
