// Sampling properties besides the χ² fit: the weight of a finite sample is f·|cos|/pdf and its
// reported pdf is pdf(wi, wo); an impulse's weight is its magnitude over its probability; the
// §27.14 energy split (mirror impulse 0.4 + Lambert albedo 0.2: 40 % impulse, 20 % finite, 40 %
// absorbed); mixtures; the helper samplers.
#include <gtest/gtest.h>

#include <cmath>

#include "appearance/dielectric.h"
#include "appearance/gltf_bsdf.h"
#include "appearance/lambert.h"
#include "appearance/microfacet_distribution.h"
#include "appearance/mirror.h"
#include "appearance/mixture.h"
#include "appearance/registry.h"
#include "appearance/rng.h"
#include "appearance/sampling.h"
#include "base/error.h"
#include "test_models.h"

namespace svbrdf::testing {
namespace {

TEST(Sampling, WeightIsFCosOverPdfAndPdfIsConsistent) {
  for (const ModelCase& mc : sampler_cases()) {
    const auto bsdf = mc.build();
    for (double theta : {0.0, 40.0, 75.0, 89.0}) {
      const glm::vec3 wo = direction_deg(theta, 33);
      Rng rng(5, 9);
      int finite = 0;
      for (int i = 0; i < 4000; ++i) {
        const BsdfSample s = bsdf->sample(wo, {rng.next_float(), rng.next_float(), rng.next_float()});
        if (s.kind == SampleKind::absorbed) {
          EXPECT_EQ(s.weight, Rgb(0));
          continue;
        }
        if (s.kind == SampleKind::impulse) {
          // The impulse is one of impulses_in(wo), and weight × probability is its magnitude (a
          // mixture scales both by the lobe weight).
          const Impulses imp = bsdf->impulses_in(wo);
          bool found = false;
          for (int k = 0; k < imp.count; ++k)
            if (glm::length(imp.items[static_cast<std::size_t>(k)].direction - s.wi) < 1e-6f) {
              found = true;
              const Rgb m = imp.items[static_cast<std::size_t>(k)].magnitude;
              for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c] * s.pdf, m[c], 1e-5 * m[c] + 1e-7) << mc.label();
            }
          EXPECT_TRUE(found) << mc.label() << ": an impulse sample must be one of impulses_in";
          continue;
        }
        ++finite;
        ASSERT_GT(s.wi.z, 0) << mc.label();
        EXPECT_NEAR(glm::length(s.wi), 1.0f, 1e-5f);
        const float p = bsdf->pdf(s.wi, wo);
        EXPECT_NEAR(s.pdf, p, 1e-4f * p) << mc.label();
        const Rgb expected = bsdf->eval(s.wi, wo) * (std::abs(s.wi.z) / p);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(s.weight[c], expected[c], 1e-4f * expected[c] + 1e-7f) << mc.label();
      }
      if (theta < 80) {
        EXPECT_GT(finite, 0) << mc.label();
      }
    }
  }
}

TEST(Sampling, TheEnergySplitOfSection27_14) {
  // Mirror impulse 0.4 + Lambert albedo 0.2, built both directly and through the registry.
  const Lambert lambert(Rgb(0.2f));
  const Mirror mirror(Rgb(1.0f));
  Mixture direct;
  direct.add(lambert, 1.0f);
  direct.add(mirror, 0.4f);
  const auto via_registry = make_model("lambert", {"albedo=0.2"}, {"mirror:0.4"});
  for (const Bsdf* bsdf : {static_cast<const Bsdf*>(&direct), static_cast<const Bsdf*>(via_registry.get())}) {
    const glm::vec3 wo = direction_deg(35, 70);
    Rng rng(2027, 14);
    const int n = 1000000;
    int finite = 0, impulse = 0, absorbed = 0;
    for (int i = 0; i < n; ++i) {
      const BsdfSample s = bsdf->sample(wo, {rng.next_float(), rng.next_float(), rng.next_float()});
      if (s.kind == SampleKind::finite) {
        ++finite;
        EXPECT_NEAR(s.weight.x, 1.0f, 1e-4f) << "albedo / probability of the finite part";
      } else if (s.kind == SampleKind::impulse) {
        ++impulse;
        EXPECT_NEAR(s.pdf, 0.4f, 1e-6f);
        EXPECT_NEAR(s.weight.x, 1.0f, 1e-5f);
      } else {
        ++absorbed;
      }
    }
    EXPECT_NEAR(impulse / double(n), 0.4, 0.004);
    EXPECT_NEAR(finite / double(n), 0.2, 0.002);
    EXPECT_NEAR(absorbed / double(n), 0.4, 0.004);
    EXPECT_NEAR(bsdf->scatter_probability(wo), 0.6f, 1e-6f);
  }
}

TEST(Sampling, DielectricSplitsByFresnel) {
  const Dielectric glass(1.5f);
  for (double theta : {0.0, 60.0, 85.0}) {
    const glm::vec3 wo = direction_deg(theta, 0);
    const Impulses imp = glass.impulses_in(wo);
    const double F = imp.items[0].magnitude.x;
    Rng rng(3, 3);
    int reflected = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const BsdfSample s = glass.sample(wo, {rng.next_float(), rng.next_float(), rng.next_float()});
      ASSERT_EQ(s.kind, SampleKind::impulse);
      if (s.wi.z > 0) {
        ++reflected;
        EXPECT_NEAR(s.weight.x, 1.0f, 1e-6f);
      } else {
        EXPECT_NEAR(s.weight.x, 1.0f / 2.25f, 1e-6f) << "the 1/η² radiance scaling";
      }
    }
    EXPECT_NEAR(reflected / double(n), F, 4 * std::sqrt(F * (1 - F) / n) + 1e-4) << "θ " << theta;
  }
  // From inside past the critical angle every sample reflects.
  EXPECT_GT(glass.sample(-direction_deg(60, 0), {0.99f, 0.5f, 0.5f}).wi.z, -1.0f);
  EXPECT_LT(glass.sample(-direction_deg(60, 0), {0.99f, 0.5f, 0.5f}).wi.z, 0.0f);
}

TEST(Mixture, IsTheWeightedSumWithoutOwningItsLobes) {
  // The shape the MIP lookup builds: gltf lobes with weights summing to 1, on the stack.
  std::array<GltfBsdf, 2> lobes = {GltfBsdf({Rgb(0.8f, 0.2f, 0.1f), 0.0f, 0.6f}), GltfBsdf({Rgb(0.9f), 1.0f, 0.15f})};
  Mixture mix;
  mix.add(lobes[0], 0.7f);
  mix.add(lobes[1], 0.3f);
  for (const glm::vec3& wi : {direction_deg(10, 0), direction_deg(60, 200), direction_deg(85, 30)})
    for (const glm::vec3& wo : {direction_deg(0, 0), direction_deg(45, 20), direction_deg(80, 100)}) {
      const Rgb expected = 0.7f * lobes[0].eval(wi, wo) + 0.3f * lobes[1].eval(wi, wo);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(mix.eval(wi, wo)[c], expected[c], 1e-6f * expected[c] + 1e-7f);
    }
  EXPECT_EQ(mix.size(), 2);
  Mixture full;
  for (int i = 0; i < Mixture::kCapacity; ++i) full.add(lobes[0], 1.0f / Mixture::kCapacity);
  EXPECT_THROW(full.add(lobes[0], 0.1f), Error);
  EXPECT_THROW(mix.add(lobes[0], -1.0f), Error);
  EXPECT_THROW(mix.add(lobes[0], NAN), Error);
}

TEST(SamplingHelpers, DensitiesIntegrateToOneAndErfInverseInverts) {
  // ∫ pdf over the hemisphere by midpoint quadrature in (θ, φ)-symmetric form.
  const int n = 20000;
  double cosine = 0, power = 0;
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) / n * 1.5707963267948966;
    const double dw = std::sin(t) * (1.5707963267948966 / n) * 6.283185307179586;
    cosine += cosine_hemisphere_pdf(static_cast<float>(std::cos(t))) * dw;
    power += power_cosine_pdf(static_cast<float>(std::cos(t)), 37.0f) * dw;
  }
  EXPECT_NEAR(cosine, 1.0, 1e-4);
  EXPECT_NEAR(power, 1.0, 1e-3);
  Rng rng(4, 4);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 w = sample_cosine_hemisphere({rng.next_float(), rng.next_float()});
    EXPECT_NEAR(glm::length(w), 1.0f, 1e-5f);
    EXPECT_GE(w.z, 0.0f);
  }
  for (float x : {-0.999f, -0.7f, -0.1f, 0.0f, 0.3f, 0.9f, 0.99999f})
    EXPECT_NEAR(std::erf(static_cast<double>(erf_inverse(x))), x, 2e-7) << x;
  // The free visible-normal densities are the distribution's.
  for (const glm::vec3& h : {direction_deg(5, 10), direction_deg(30, 200), direction_deg(70, 80)}) {
    const glm::vec3 wo = direction_deg(60, 40);
    EXPECT_FLOAT_EQ(ggx_visible_pdf(0.3f, wo, h), (MicrofacetDistribution{MicrofacetType::ggx, 0.3f}.visible_pdf(wo, h)));
    EXPECT_FLOAT_EQ(beckmann_visible_pdf(0.3f, wo, h),
                    (MicrofacetDistribution{MicrofacetType::beckmann, 0.3f}.visible_pdf(wo, h)));
  }
  // Visible normals face the viewer.
  const MicrofacetDistribution d{MicrofacetType::beckmann, 0.4f};
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 wo = direction_deg(88, 30);
    const glm::vec3 h = d.sample_visible(wo, {rng.next_float(), rng.next_float()});
    EXPECT_GT(glm::dot(h, wo), 0.0f);
    EXPECT_GT(h.z, 0.0f);
  }
}

}  // namespace
}  // namespace svbrdf::testing
