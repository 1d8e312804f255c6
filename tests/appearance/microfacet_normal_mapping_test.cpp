// Microfacet-based normal mapping (appearance/microfacet_normal_mapping.h) against what holds
// independently of its code: the inner model itself when wp = wg, the paper's formulas re-derived
// here in double, reciprocity, energy conservation (white furnace), its sampler against its own
// density (χ²), and finiteness at the extremes.
#include "appearance/microfacet_normal_mapping.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "appearance/dielectric.h"
#include "appearance/lambert.h"
#include "appearance/microfacet.h"
#include "appearance/mirror.h"
#include "appearance/rng.h"
#include "chi2.h"
#include "test_models.h"

namespace svbrdf::testing {
namespace {

constexpr double kPiD = 3.14159265358979323846;

// Inner models: a white and a grey Lambert, a glossy GGX over a diffuse base.
std::unique_ptr<Bsdf> glossy() {
  MicrofacetParams p;
  p.alpha = 0.3f;
  p.kd = Rgb(0.3f);
  return std::make_unique<Microfacet>(p);
}

// Directions in the geometric frame that cover the hemisphere, grazing ones included.
std::vector<glm::vec3> hemisphere_directions() {
  std::vector<glm::vec3> out;
  for (double theta : {0.0, 20.0, 45.0, 70.0, 85.0, 89.5})
    for (double phi : {0.0, 50.0, 90.0, 140.0, 180.0, 235.0, 300.0}) out.push_back(direction_deg(theta, phi));
  return out;
}

// The paper's quantities for a perturbed normal wp, written from its definitions in double, and its
// explicit evaluation with the fourth path (wo → wt → wp → wt → wi) for a Lambert inner model of
// albedo rho (isotropic, so the inner frame's tangent does not matter).
struct PaperReference {
  glm::dvec3 wp, wt;
  double cp, sp;
  explicit PaperReference(const glm::vec3& n) {
    wp = glm::normalize(glm::dvec3(n));
    cp = wp.z;
    sp = std::sqrt(1 - cp * cp);
    wt = -glm::normalize(glm::dvec3(wp.x, wp.y, 0));
  }
  double ap(const glm::dvec3& w) const { return std::max(0.0, glm::dot(w, wp)) / cp; }
  double at(const glm::dvec3& w) const { return std::max(0.0, glm::dot(w, wt)) * sp / cp; }
  double lambda_p(const glm::dvec3& w) const { return ap(w) / (ap(w) + at(w)); }
  double g1(const glm::dvec3& w, const glm::dvec3& wm) const {
    return glm::dot(w, wm) > 0 ? std::min(1.0, std::max(0.0, w.z) / (ap(w) + at(w))) : 0.0;
  }
  glm::dvec3 mirror(const glm::dvec3& w) const { return w - 2 * glm::dot(w, wt) * wt; }
  double lambert(const glm::dvec3& wi, const glm::dvec3& wo, double rho) const {
    return glm::dot(wi, wp) > 0 && glm::dot(wo, wp) > 0 ? rho / kPiD : 0.0;
  }
  double eval(const glm::dvec3& wi, const glm::dvec3& wo, double rho) const {
    if (wi.z <= 0 || wo.z <= 0) return 0;
    const double lp = lambda_p(wo), lt = 1 - lp;
    const glm::dvec3 wi_m = mirror(wi), wo_m = mirror(wo);
    const double direct = lp * lambert(wi, wo, rho) * glm::dot(wi, wp) * g1(wi, wp);
    const double via_t = lp * lambert(wi_m, wo, rho) * glm::dot(wi_m, wp) * (1 - g1(wi_m, wp)) * g1(wi, wt);
    const double t_first = lt * lambert(wi, wo_m, rho) * glm::dot(wi, wp) * g1(wi, wp);
    // wo → wt → wp → wt → wi: the ray mirrored by wt meets wp for sure, then leaves as in via_t.
    const double t_both = lt * lambert(wi_m, wo_m, rho) * glm::dot(wi_m, wp) * (1 - g1(wi_m, wp)) * g1(wi, wt);
    return (direct + via_t + t_first + t_both) / wi.z;
  }
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

TEST(MicrofacetNormalMapping, PassesThroughWhenWpIsWg) {
  const Lambert lambert(Rgb(0.7f, 0.5f, 0.3f));
  const auto ggx = glossy();
  const Mirror mirror(Rgb(0.9f));
  const Dielectric glass(1.5f);
  const Bsdf* inners[] = {&lambert, ggx.get(), &mirror, &glass};
  for (const Bsdf* inner : inners)
    for (const glm::vec3 wp : {glm::vec3(0, 0, 1), glm::vec3(0, 0, 2.5f)}) {
      const MicrofacetNormalMapping m(*inner, wp);
      ASSERT_TRUE(m.passes_through());
      Rng rng(5, 11);
      for (const glm::vec3& wo : hemisphere_directions()) {
        EXPECT_EQ(m.scatter_probability(wo), inner->scatter_probability(wo));
        for (const glm::vec3& wi : hemisphere_directions()) {
          EXPECT_EQ(m.eval(wi, wo), inner->eval(wi, wo));
          EXPECT_EQ(m.pdf(wi, wo), inner->pdf(wi, wo));
        }
        for (int k = 0; k < 20; ++k) {
          const SampleU u(rng.next_float(), rng.next_float(), rng.next_float());
          const BsdfSample a = m.sample(wo, u), b = inner->sample(wo, u);
          EXPECT_EQ(a.kind, b.kind);
          EXPECT_EQ(a.wi, b.wi);
          EXPECT_EQ(a.pdf, b.pdf);
          EXPECT_EQ(a.weight, b.weight);
        }
        const Impulses ia = m.impulses_in(wo), ib = inner->impulses_in(wo);
        const Impulses oa = m.impulses_out(wo), ob = inner->impulses_out(wo);
        ASSERT_EQ(ia.count, ib.count);
        ASSERT_EQ(oa.count, ob.count);
        for (int i = 0; i < ia.count; ++i) {
          const auto k = static_cast<std::size_t>(i);
          EXPECT_EQ(ia.items[k].direction, ib.items[k].direction);
          EXPECT_EQ(ia.items[k].magnitude, ib.items[k].magnitude);
          EXPECT_EQ(oa.items[k].direction, ob.items[k].direction);
          EXPECT_EQ(oa.items[k].magnitude, ob.items[k].magnitude);
        }
      }
    }
}

TEST(MicrofacetNormalMapping, PerturbedFrameFollowsTheGeometricTangent) {
  for (const glm::vec3 wp : {direction_deg(30, 0), direction_deg(60, 40), direction_deg(80, 200)}) {
    const Lambert inner;
    const MicrofacetNormalMapping m(inner, wp);
    const Frame& f = m.perturbed_frame();
    const glm::dvec3 x(1, 0, 0), n(wp);
    const glm::dvec3 s = glm::normalize(x - n * glm::dot(n, x));  // Gram–Schmidt of the tangent
    EXPECT_NEAR(glm::distance(glm::dvec3(f.n), n), 0.0, 1e-6);
    EXPECT_NEAR(glm::distance(glm::dvec3(f.s), s), 0.0, 1e-6);
    EXPECT_NEAR(glm::dot(glm::dvec3(f.t), glm::cross(n, s)), 1.0, 1e-6);
    // wt is perpendicular to wg and faces away from wp's tilt.
    EXPECT_NEAR(m.wt().z, 0.0f, 1e-7f);
    EXPECT_LT(glm::dot(m.wt(), wp), 0.0f);
  }
}

TEST(MicrofacetNormalMapping, EvalFollowsThePaperFormulas) {
  for (const glm::vec3 wp : {direction_deg(20, 10), direction_deg(60, 0), direction_deg(80, 130)}) {
    const Lambert inner(Rgb(0.8f));
    const MicrofacetNormalMapping m(inner, wp);
    const PaperReference ref(wp);
    for (const glm::vec3& wo : hemisphere_directions())
      for (const glm::vec3& wi : hemisphere_directions()) {
        const double want = ref.eval(glm::dvec3(wi), glm::dvec3(wo), 0.8);
        EXPECT_NEAR(m.eval(wi, wo).x, want, 2e-4 * want + 1e-6) << "wi " << wi.x << " " << wi.y << " " << wi.z
                                                                << ", wo " << wo.x << " " << wo.y << " " << wo.z;
      }
  }
}

TEST(MicrofacetNormalMapping, EvalIsReciprocal) {
  const Lambert lambert(Rgb(0.8f));
  const auto ggx = glossy();
  for (const Bsdf* inner : {static_cast<const Bsdf*>(&lambert), static_cast<const Bsdf*>(ggx.get())})
    for (const glm::vec3 wp : {direction_deg(35, 70), direction_deg(70, 250)}) {
      const MicrofacetNormalMapping m(*inner, wp);
      for (const glm::vec3& wo : hemisphere_directions())
        for (const glm::vec3& wi : hemisphere_directions()) {
          const float a = m.eval(wi, wo).x, b = m.eval(wo, wi).x;
          EXPECT_NEAR(a, b, 1e-3f * std::max(a, b) + 1e-6f);
        }
    }
}

// ∫ f cosθi dωi from sample weights (the whole model: explicit paths and the walk) and from eval
// alone (Monte Carlo over the uniform hemisphere, the explicit paths only).
struct Albedo {
  double sampled = 0, sampled_se = 0, explicit_share = 0, evaluated = 0, evaluated_se = 0;
};

Albedo albedo(const Bsdf& b, const glm::vec3& wo, int n, std::uint64_t seed) {
  Rng rng(seed, 3);
  double s = 0, s2 = 0, finite_sum = 0;
  for (int i = 0; i < n; ++i) {
    const BsdfSample bs = b.sample(wo, SampleU(rng.next_float(), rng.next_float(), rng.next_float()));
    const double w = bs.kind == SampleKind::absorbed ? 0.0 : bs.weight.x;
    s += w;
    s2 += w * w;
    if (bs.kind == SampleKind::finite) finite_sum += w;
  }
  Albedo a;
  a.sampled = s / n;
  a.sampled_se = std::sqrt(std::max(0.0, s2 / n - a.sampled * a.sampled) / n);
  a.explicit_share = finite_sum / n;
  double e = 0, e2 = 0;
  for (int i = 0; i < n; ++i) {
    const double z = rng.next_double(), phi = 2 * kPiD * rng.next_double(), r = std::sqrt(1 - z * z);
    const glm::vec3 wi(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)), static_cast<float>(z));
    const double v = b.eval(wi, wo).x * wi.z * 2 * kPiD;  // f cosθ / (1/2π)
    e += v;
    e2 += v * v;
  }
  a.evaluated = e / n;
  a.evaluated_se = std::sqrt(std::max(0.0, e2 / n - a.evaluated * a.evaluated) / n);
  return a;
}

TEST(MicrofacetNormalMapping, WhiteFurnaceKeepsEnergy) {
  const Lambert white(Rgb(1.0f));
  for (double tilt : {60.0, 80.0}) {
    const glm::vec3 wp = direction_deg(tilt, 30);
    const MicrofacetNormalMapping m(white, wp);
    std::uint64_t seed = 1;
    for (double theta : {0.0, 30.0, 60.0, 85.0})
      for (double phi : {30.0, 120.0, 210.0}) {
        const glm::vec3 wo = direction_deg(theta, phi);
        const Albedo a = albedo(m, wo, 200000, seed++);
        std::printf("furnace wp %2.0f°, wo (%2.0f°, %3.0f°): sampled %.6f ± %.1e (finite %.3f), eval %.4f ± %.4f\n",
                    tilt, theta, phi, a.sampled, a.sampled_se, a.explicit_share, a.evaluated, a.evaluated_se);
        EXPECT_NEAR(a.sampled, 1.0, 4 * a.sampled_se + 1e-4) << "wp " << tilt << ", wo " << theta << " " << phi;
        EXPECT_LE(a.evaluated, 1.0 + 4 * a.evaluated_se) << "wp " << tilt << ", wo " << theta << " " << phi;
        // Next-event estimation sees the explicit paths: eval's albedo is what the finite samples carry.
        EXPECT_NEAR(a.evaluated, a.explicit_share, 4 * a.evaluated_se + 0.01) << "wp " << tilt;
        // In the furnace the wp facets (area 1/<wp, wg> per unit geometric area) emit πL/<wp, wg> of
        // which πL leaves: after a Lambertian scattering on wp the light leaves before meeting wp
        // again with probability <wp, wg>. eval's four paths are every path with one scattering on
        // wp, so they hold exactly that share, whichever facet the viewer meets first.
        EXPECT_NEAR(a.evaluated, wp.z, 4 * a.evaluated_se + 2e-3) << "wp " << tilt;
      }
  }
}

// eval holds every path with one scattering on wp (see the header): after a Lambertian scattering on
// wp the light leaves before meeting wp again with probability <wp, wg>, so with a white Lambert
// inner model eval's directional albedo is <wp, wg> for every viewer, one that sees only wt too.
TEST(MicrofacetNormalMapping, EvalHoldsEverySingleScatteringOnWp) {
  const Lambert white(Rgb(1.0f));
  std::uint64_t seed = 90;
  for (double tilt : {30.0, 60.0, 80.0}) {
    const glm::vec3 wp = direction_deg(tilt, 0);  // wt = −x
    const MicrofacetNormalMapping m(white, wp);
    for (const glm::vec3 wo : {direction_deg(40, 0), direction_deg(40, 180), direction_deg(70, 180)}) {
      const Albedo a = albedo(m, wo, 200000, seed++);
      std::printf("eval albedo wp %2.0f°, wo %s wt, <wo, wp> %+.2f: %.4f ± %.4f (sampled %.4f)\n", tilt,
                  glm::dot(wo, m.wt()) > 0 ? "facing" : "not facing", glm::dot(wo, wp), a.evaluated, a.evaluated_se,
                  a.sampled);
      EXPECT_NEAR(a.evaluated, wp.z, 4 * a.evaluated_se + 2e-3) << "wp " << tilt << ", wo " << wo.x << " " << wo.z;
    }
  }
}

// The same argument with an absorbing Lambert inner model of albedo ρ: every scattering on wp keeps ρ,
// and the number of them is geometric with escape probability c = <wp, wg>, so the directional
// albedo is Σ_n ρⁿ c (1 − c)ⁿ⁻¹ = ρc / (1 − ρ(1 − c)), for every wo.
TEST(MicrofacetNormalMapping, GreyFurnaceFollowsTheEscapeRate) {
  for (float rho : {0.5f, 0.8f})
    for (double tilt : {45.0, 80.0}) {
      const Lambert grey{Rgb(rho)};
      const glm::vec3 wp = direction_deg(tilt, 100);
      const MicrofacetNormalMapping m(grey, wp);
      const double c = wp.z, want = rho * c / (1 - rho * (1 - c));
      std::uint64_t seed = 40;
      for (const glm::vec3 wo : {direction_deg(10, 0), direction_deg(55, 100), direction_deg(70, 280)}) {
        const Albedo a = albedo(m, wo, 200000, seed++);
        EXPECT_NEAR(a.sampled, want, 4 * a.sampled_se + 1e-4) << "ρ " << rho << ", wp " << tilt;
      }
    }
}

TEST(MicrofacetNormalMapping, SamplesFollowPdf) {
  const Lambert lambert(Rgb(0.8f));
  const auto ggx = glossy();
  const Bsdf* inners[] = {&lambert, ggx.get()};
  constexpr double kTilt[] = {30, 60, 80}, kThetaO[] = {0, 45, 75};
  const double alpha = 0.01 / static_cast<double>(std::size(inners) * std::size(kTilt) * std::size(kThetaO));
  std::uint64_t seed = 77;
  for (const Bsdf* inner : inners)
    for (double tilt : kTilt) {
      const MicrofacetNormalMapping m(*inner, direction_deg(tilt, 15));
      int k = 0;
      for (double theta : kThetaO) {
        const glm::vec3 wo = direction_deg(theta, 40.0 + 110.0 * k++);
        Chi2Options opt;
        opt.seed = seed++;
        const Chi2Result r = chi2_test(m, wo, opt);
        EXPECT_GT(r.p_value, alpha) << "wp " << tilt << "°, θo " << theta << ": χ² = " << r.statistic << " with "
                                    << r.dof << " dof; worst " << r.worst;
        const double f = r.finite_fraction, se = std::sqrt(std::max(f * (1 - f), 1e-12) / opt.samples);
        EXPECT_NEAR(r.pdf_integral, f, 0.01 * f + 4 * se) << "wp " << tilt << "°, θo " << theta;
      }
    }
}

TEST(MicrofacetNormalMapping, FiniteSampleWeightIsEvalCosOverPdf) {
  const Lambert lambert(Rgb(0.6f, 0.4f, 0.2f));
  const auto ggx = glossy();
  for (const Bsdf* inner : {static_cast<const Bsdf*>(&lambert), static_cast<const Bsdf*>(ggx.get())})
    for (double tilt : {25.0, 65.0, 85.0}) {
      const MicrofacetNormalMapping m(*inner, direction_deg(tilt, 200));
      Rng rng(9, 1);
      int finite_samples = 0, seeing_only_wt = 0;
      for (const glm::vec3& wo : hemisphere_directions())
        for (int i = 0; i < 200; ++i) {
          const BsdfSample s = m.sample(wo, SampleU(rng.next_float(), rng.next_float(), rng.next_float()));
          if (s.kind != SampleKind::finite) continue;
          ++finite_samples;
          seeing_only_wt += glm::dot(wo, m.perturbed_frame().n) <= 0;  // through wo → wt → wp (→ wt) → wi
          EXPECT_NEAR(s.pdf, m.pdf(s.wi, wo), 1e-5f * s.pdf);
          const Rgb want = m.eval(s.wi, wo) * (s.wi.z / m.pdf(s.wi, wo));
          for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], want[c], 1e-4f * want[c] + 1e-7f);
        }
      EXPECT_GT(finite_samples, 100);
      if (tilt > 60) {
        EXPECT_GT(seeing_only_wt, 10) << "wp " << tilt;
      }
    }
}

TEST(MicrofacetNormalMapping, NoBlackTerminator) {
  // wp 60° toward +x; the light at 70° toward −x: above the geometric surface, behind wp.
  const glm::vec3 wp = direction_deg(60, 0), wi = direction_deg(70, 180);
  ASSERT_GT(wi.z, 0.0f);
  ASSERT_LT(glm::dot(wi, wp), 0.0f);
  const Lambert inner(Rgb(0.8f));
  const MicrofacetNormalMapping m(inner, wp);
  const Frame shading = Frame::from_normal(wp);
  // Viewers that see wp: the tangent facet mirrors the light onto wp (wo → wp → wt → wi).
  for (const glm::vec3 wo : {direction_deg(0, 0), direction_deg(40, 0), direction_deg(20, 180), direction_deg(75, 90)}) {
    ASSERT_GT(glm::dot(wo, wp), 0.0f);
    // Classic normal mapping shades in the frame of wp: black.
    EXPECT_EQ(inner.eval(shading.to_local(wi), shading.to_local(wo)).x, 0.0f);
    EXPECT_GT(m.eval(wi, wo).x * wi.z, 1e-3f) << "wo " << wo.x << " " << wo.y << " " << wo.z;
  }
  // A viewer that sees only wt (wo · wp < 0) meets this light through wo → wt → wp → wt → wi alone:
  // eval holds it (a delta light reaches it), as the independent reference writes it.
  const PaperReference ref(wp);
  for (const glm::vec3 wo : {direction_deg(40, 180), direction_deg(70, 180), direction_deg(60, 150)}) {
    ASSERT_LT(glm::dot(wo, wp), 0.0f);
    const double want = ref.eval(glm::dvec3(wi), glm::dvec3(wo), 0.8);
    EXPECT_GT(want * wi.z, 1e-3);
    EXPECT_NEAR(m.eval(wi, wo).x, want, 2e-4 * want) << "wo " << wo.x << " " << wo.y << " " << wo.z;
    EXPECT_GT(m.pdf(wi, wo), 0.0f);
  }
}

TEST(MicrofacetNormalMapping, StaysFiniteAtExtremes) {
  const Lambert lambert(Rgb(0.8f));
  const auto ggx = glossy();
  const Mirror mirror(Rgb(1.0f));
  const Dielectric glass(1.5f);
  const Bsdf* inners[] = {&lambert, ggx.get(), &mirror, &glass};
  std::vector<glm::vec3> wps;
  for (float c : {1e-4f, 1e-3f, 0.01f, 0.05f, 0.3f, -0.3f, -1.0f}) {
    const float s = std::sqrt(std::max(0.0f, 1 - c * c));
    wps.push_back({s * 0.6f, s * 0.8f, c});
  }
  wps.push_back({1e-20f, 0, 1});  // a tilt below float resolution
  std::vector<glm::vec3> dirs = hemisphere_directions();
  for (float z : {1e-7f, 1e-4f, 1e-2f})
    for (double phi = 0; phi < 360; phi += 22.5) {
      const float r = std::sqrt(1 - z * z);
      dirs.push_back({r * static_cast<float>(std::cos(phi * kPiD / 180)), r * static_cast<float>(std::sin(phi * kPiD / 180)), z});
    }
  dirs.push_back({0.6f, 0.8f, 0.0f});   // horizontal
  dirs.push_back({-0.8f, 0.6f, 0.0f});  // horizontal along the groove of the first wps
  for (const Bsdf* inner : inners)
    for (const glm::vec3& wp : wps) {
      const MicrofacetNormalMapping m(*inner, wp);
      EXPECT_GE(m.perturbed_frame().n.z, MicrofacetNormalMapping::kMinCosWp - 1e-6f);
      Rng rng(3, 4);
      for (const glm::vec3& wo : dirs) {
        const float p = m.scatter_probability(wo);
        EXPECT_TRUE(std::isfinite(p) && p >= 0 && p <= 1.0f + 1e-6f);
        for (const glm::vec3& wi : dirs) {
          const Rgb f = m.eval(wi, wo);
          const float pdf = m.pdf(wi, wo);
          ASSERT_TRUE(finite(f) && f.x >= 0 && f.y >= 0 && f.z >= 0) << wp.z << " " << wi.z << " " << wo.z;
          ASSERT_TRUE(std::isfinite(pdf) && pdf >= 0) << wp.z << " " << wi.z << " " << wo.z;
          ASSERT_TRUE(std::isfinite(f.x * wi.z));
        }
        for (int i = 0; i < 50; ++i) {
          const BsdfSample s = m.sample(wo, SampleU(rng.next_float(), rng.next_float(), rng.next_float()));
          ASSERT_TRUE(finite(s.weight) && finite(s.wi) && std::isfinite(s.pdf)) << wp.z << " " << wo.z;
          if (s.kind != SampleKind::absorbed) {
            ASSERT_GT(s.pdf, 0.0f);
          }
        }
        for (const Impulses& imps : {m.impulses_in(wo), m.impulses_out(wo)})
          for (int i = 0; i < imps.count; ++i) {
            const Impulse& imp = imps.items[static_cast<std::size_t>(i)];
            ASSERT_TRUE(finite(imp.direction) && finite(imp.magnitude));
          }
      }
    }
}

TEST(MicrofacetNormalMapping, InnerImpulsesPassThroughWp) {
  // A white mirror as the inner model: every walk ends in an impulse; no energy is lost.
  const Mirror white(Rgb(1.0f));
  const glm::vec3 wp = direction_deg(30, 0);
  const MicrofacetNormalMapping m(white, wp);
  const PaperReference ref(wp);
  for (const glm::vec3 wo : {direction_deg(20, 180), direction_deg(50, 150), direction_deg(35, 20)}) {
    // wo → wp → wi: the mirror direction of wo about wp, with λp(wo) G1(wi, wp) (the paper's factors).
    const glm::dvec3 r = 2.0 * glm::dot(glm::dvec3(wo), ref.wp) * ref.wp - glm::dvec3(wo);
    const double want = ref.lambda_p(glm::dvec3(wo)) * ref.g1(r, ref.wp);
    const Impulses in = m.impulses_in(wo);
    bool found = false;
    for (int i = 0; i < in.count; ++i) {
      const Impulse& imp = in.items[static_cast<std::size_t>(i)];
      if (glm::dot(glm::dvec3(imp.direction), r) > 1 - 1e-6) {
        found = true;
        EXPECT_NEAR(imp.magnitude.x, want, 1e-4);
        // Reciprocity through impulses_out, where it keeps the same path.
        const Impulses out = m.impulses_out(imp.direction);
        for (int j = 0; j < out.count; ++j) {
          if (glm::dot(out.items[static_cast<std::size_t>(j)].direction, wo) > 1 - 1e-6f) {
            EXPECT_NEAR(out.items[static_cast<std::size_t>(j)].magnitude.x, imp.magnitude.x, 1e-4f);
          }
        }
      }
    }
    EXPECT_EQ(found, want > 1e-3) << "wo " << wo.x << " " << wo.y << " " << wo.z;
    // sample(): impulses only, weight 1 each (white mirrors), energy kept. A walk that takes a listed
    // path has weight × pdf = that path's probability, its magnitude, and the share of such samples
    // is the magnitude. Longer walks can leave along the same direction (wo → wp → wt → wp → wi
    // below the horizon and wo → wt → wp → wt → wi, two facets being a reflection group), with the
    // probability of their own choices: along a listed impulse at least its magnitude leaves.
    Rng rng(21, 2);
    const int n = 100000;
    double total = 0;
    std::vector<double> along(static_cast<std::size_t>(in.count), 0.0), by_path(along);
    for (int i = 0; i < n; ++i) {
      const BsdfSample s = m.sample(wo, SampleU(rng.next_float(), rng.next_float(), rng.next_float()));
      ASSERT_NE(s.kind, SampleKind::finite);
      if (s.kind == SampleKind::absorbed) continue;
      total += s.weight.x;
      for (int k = 0; k < in.count; ++k) {
        const auto ks = static_cast<std::size_t>(k);
        if (glm::dot(s.wi, in.items[ks].direction) > 1 - 1e-6f) {
          along[ks] += s.weight.x;
          if (std::abs(s.weight.x * s.pdf - in.items[ks].magnitude.x) < 1e-4f) by_path[ks] += s.weight.x;
        }
      }
    }
    EXPECT_NEAR(total / n, 1.0, 1e-4);
    for (int k = 0; k < in.count; ++k) {
      const auto ks = static_cast<std::size_t>(k);
      const double mk = in.items[ks].magnitude.x;
      EXPECT_NEAR(by_path[ks] / n, mk, 4 * std::sqrt(mk / n) + 1e-4) << "wo " << wo.x << " " << wo.y << " " << wo.z;
      EXPECT_GE(along[ks] / n, mk - 4 * std::sqrt(mk / n) - 1e-4);
    }
  }
}

}  // namespace
}  // namespace svbrdf::testing
