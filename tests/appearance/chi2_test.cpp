// χ² goodness of fit of every sampler against its own pdf, at several wo including near-grazing,
// with a Bonferroni-corrected significance level; and the harness itself must reject a wrong pdf.
#include "chi2.h"

#include <gtest/gtest.h>

#include <cstdlib>

#include "appearance/lambert.h"
#include "appearance/sampling.h"
#include "test_models.h"

namespace svbrdf::testing {
namespace {

// θo (degrees) of the wo at which every sampler is tested; azimuths vary so no case lines up
// with the binning grid.
constexpr double kThetaO[] = {0, 35, 65, 80, 88};

// Family-wise significance 1 %, split evenly over every χ² test of this file (Bonferroni).
double per_test_significance() {
  const double tests = static_cast<double>(sampler_cases().size() * std::size(kThetaO) + 1);
  return 0.01 / tests;
}

class SamplerChi2 : public ::testing::TestWithParam<std::size_t> {};

TEST_P(SamplerChi2, SamplesFollowTheirPdf) {
  const ModelCase& mc = sampler_cases()[GetParam()];
  const auto bsdf = mc.build();
  int k = 0;
  for (double theta : kThetaO) {
    const glm::vec3 wo = direction_deg(theta, 20.0 + 47.0 * k);
    Chi2Options opt;
    opt.seed = 1000 + GetParam() * 17 + static_cast<std::uint64_t>(k++);
    const Chi2Result r = chi2_test(*bsdf, wo, opt);
    EXPECT_GT(r.p_value, per_test_significance())
        << mc.label() << " at θo = " << theta << ": χ² = " << r.statistic << " with " << r.dof << " dof ("
        << r.leaves << " leaves); worst " << r.worst;
    // The density integrates to the probability of a finite sample (1 % + 4 standard errors).
    const double f = r.finite_fraction, se = std::sqrt(std::max(f * (1 - f), 1e-12) / opt.samples);
    EXPECT_NEAR(r.pdf_integral, f, 0.01 * f + 4 * se) << mc.label() << " at θo = " << theta;
  }
}

INSTANTIATE_TEST_SUITE_P(AllSamplers, SamplerChi2, ::testing::Range<std::size_t>(0, sampler_cases().size()),
                         [](const ::testing::TestParamInfo<std::size_t>& info) {
                           std::string s = sampler_cases()[info.param].name + "_" + std::to_string(info.param);
                           for (char& c : s)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return s;
                         });

// The heavier variant (ctest label `long`, run with SVBRDF_LONG=1): ten times the samples and more
// directions, down to 89.5°. Its own Bonferroni correction.
TEST(LongSamplerChi2, AllSamplersManyDirections) {
  if (!std::getenv("SVBRDF_LONG")) GTEST_SKIP() << "set SVBRDF_LONG=1 (ctest -L long)";
  constexpr double kTheta[] = {0, 10, 25, 45, 60, 70, 78, 84, 87, 89.5};
  const double alpha = 0.01 / static_cast<double>(sampler_cases().size() * std::size(kTheta));
  for (std::size_t c = 0; c < sampler_cases().size(); ++c) {
    const ModelCase& mc = sampler_cases()[c];
    const auto bsdf = mc.build();
    for (std::size_t k = 0; k < std::size(kTheta); ++k) {
      Chi2Options opt;
      opt.samples = 1000000;
      opt.max_depth = 12;
      opt.seed = 90000 + c * 31 + k;
      const Chi2Result r = chi2_test(*bsdf, direction_deg(kTheta[k], 11.0 + 37.0 * static_cast<double>(k)), opt);
      EXPECT_GT(r.p_value, alpha) << mc.label() << " at θo = " << kTheta[k] << ": χ² = " << r.statistic << " with "
                                  << r.dof << " dof; worst " << r.worst;
      const double f = r.finite_fraction, se = std::sqrt(std::max(f * (1 - f), 1e-12) / opt.samples);
      EXPECT_NEAR(r.pdf_integral, f, 0.01 * f + 4 * se) << mc.label() << " at θo = " << kTheta[k];
    }
  }
}

// The harness must be able to fail: a Lambert sampler whose pdf claims a slightly different shape
// (cos^1.15 instead of cos, renormalized) is rejected far below the significance level.
class WrongPdf final : public Bsdf {
 public:
  Rgb eval(const glm::vec3&, const glm::vec3&) const override { return Rgb(0.3f); }
  BsdfSample sample(const glm::vec3& wo, const SampleU& u) const override { return inner_.sample(wo, u); }
  float pdf(const glm::vec3& wi, const glm::vec3&) const override {
    return wi.z > 0 ? 2.15f / kTwoPi * std::pow(wi.z, 1.15f) : 0.0f;
  }

 private:
  Lambert inner_{Rgb(1.0f)};
};

TEST(Chi2Harness, RejectsAWrongPdfAndAcceptsTheRightOne) {
  const WrongPdf wrong;
  const Chi2Result bad = chi2_test(wrong, direction_deg(30, 10));
  EXPECT_LT(bad.p_value, per_test_significance() * 1e-3) << "χ² = " << bad.statistic << ", dof " << bad.dof;
  const Lambert right(Rgb(1.0f));
  const Chi2Result good = chi2_test(right, direction_deg(30, 10));
  EXPECT_GT(good.p_value, per_test_significance());
  EXPECT_NEAR(good.pdf_integral, 1.0, 1e-4);
}

TEST(Chi2Harness, SurvivalFunctionMatchesKnownQuantiles) {
  // Tabulated χ² quantiles: P(X > 3.841) = 0.05 for 1 dof; P(X > 18.307) = 0.05 for 10 dof;
  // P(X > 135.807) = 0.01 for 100 dof; with 2 dof the survival is exp(−x/2) exactly.
  EXPECT_NEAR(chi2_survival(3.841459, 1), 0.05, 1e-6);
  EXPECT_NEAR(chi2_survival(18.307038, 10), 0.05, 1e-6);
  EXPECT_NEAR(chi2_survival(135.806723, 100), 0.01, 1e-6);
  EXPECT_NEAR(chi2_survival(7.0, 2), std::exp(-3.5), 1e-12);
}

}  // namespace
}  // namespace svbrdf::testing
