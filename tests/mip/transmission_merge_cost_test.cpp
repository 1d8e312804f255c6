// The merge cost's transmission terms (mip/merge_cost.cpp, trans_cost; docs/mip-algorithm.md §4.6)
// against their definition, evaluated here from the lobes' moments and lobe shapes: the log profile
// of the transmission is taken over the steps at and above the cost model's resolution only.
#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "mip/lobe.h"
#include "mip/lobe_reduction.h"
#include "mip/merge_cost.h"

namespace svbrdf {
namespace {

using namespace reduction;

// A lobe that transmits τ through GGX of α²_T about the geometric normal and reflects nothing (F0 =
// F90 = 0, no diffuse part), so that union_cost is its transmission terms alone.
Lobe transmitting(double tau, double alpha2_t) {
  Lobe l;
  l.weight = 1.0f;
  l.f90 = 0.0f;
  l.alpha2 = 0.25f;
  l.transmission = l.transmission90 = glm::vec3(static_cast<float>(tau));
  l.transmission_alpha2 = static_cast<float>(alpha2_t);
  return l;
}

// D of a lobe's transmission shape at tan²θ = t from its normal (d_at_tan2, not the summary's profile).
double transmission_d(const Lobe& l, double t) {
  return d_at_tan2(DShape::of(transmission_shape(l, lobe_shape<double>(l))), t);
}

TEST(TransmissionMergeCost, TheProfileStartsAtTheResolution) {
  ASSERT_LT(profile_step(kResolvedProfileStep - 1), kResolutionAlpha2);
  ASSERT_NEAR(profile_step(kResolvedProfileStep), kResolutionAlpha2, 1e-12);

  // One lobe, GGX of α²_T = 10⁻⁴, replaced by a band of the same peak P = 10⁴ and twice its tail A:
  // below the resolution they differ in shape about the peak, above it D ≈ A/(π·t²) twice as high.
  const double tau = 0.5;
  const Lobe a = transmitting(tau, 1e-4);
  Lobe m = transmitting(tau, 1e-4);
  set_transmission_shape(m, 2e-4, 1e4);
  ASSERT_GT(m.transmission_alpha2_hi, m.transmission_alpha2);
  const Summary sa = summarize(a), sm = summarize(m);
  const std::array<Member, 1> u{Member{&a, &sa}};
  const double cost = union_cost(u, union_terms(u), sm, true, kPeakWeight);

  // The definition (merge_cost.h, trans_cost) for a grey τ: the Gaussian model's L2 error, the peak,
  // the tail and the mean log profile over the resolved steps, each times τ².
  const TransmissionMoments ma = transmission_moments(a), mm = transmission_moments(m);
  const double l2 = trans_inner(1 / ma.peak, 1 / ma.peak) - 2 * trans_inner(1 / ma.peak, 1 / mm.peak) +
                    trans_inner(1 / mm.peak, 1 / mm.peak);
  const double peak = (ma.peak - mm.peak) / kPiD, width = ma.tail - mm.tail;
  const double width_norm = 3 * kPiD * std::pow(kResolutionAlpha2, 3);
  double resolved = 0, below = 0;
  for (std::size_t j = 0; j < kProfileSteps; ++j) {
    const double ln = std::log(transmission_d(m, profile_step(j)) / transmission_d(a, profile_step(j)));
    (j < kResolvedProfileStep ? below : resolved) += ln * ln;
  }
  const double profile = resolved / double(kProfileSteps - kResolvedProfileStep);
  const double want = tau * tau * (l2 + kPeakWeight * peak * peak + width * width / width_norm + kProfileWeight * profile);
  EXPECT_NEAR(cost, want, 1e-3 * want);
  // The steps below the resolution would have changed it: their mean square log ratio differs from the
  // resolved steps' by more than a tenth.
  EXPECT_GT(std::abs(below / double(kResolvedProfileStep) - profile), 0.1 * profile);
}

}  // namespace
}  // namespace svbrdf
