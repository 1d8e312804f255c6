#pragma once
// A χ² goodness-of-fit test of a BSDF sampler against its own density (the approach of Mitsuba's
// and pbrt's sampling tests, written for this project): sample(wo, u) is run N times; the finite
// directions are binned on the sphere, the expected count of each bin is N ∫_bin pdf(wi, wo) dwi,
// and everything that is not finite (impulses, absorbed) forms one more bin whose expected count is
// N (1 − ∫ pdf). So the test checks both the shape of the density and that it integrates to the
// probability of a finite sample.
//
// Bins adapt to the sampler: the sphere is the cube [−1, 1]³ projected (no singular poles; the
// horizon is a grid line of the four side faces), 8 × 8 cells a face to start; a cell is split into
// quadrants where a pilot run (another seed, N/4 samples) puts many samples, or more or fewer than
// the quadrature predicts, where the density's mass is large, or where two quadrature levels
// disagree. Leaves expecting fewer than 5 samples are pooled with their neighbours in traversal
// order. Bin masses come from 4 × 4 Gauss–Legendre quadrature (with the cube map's Jacobian) on
// each quadrant of a leaf. The p-value is the χ² survival function (regularized upper incomplete
// gamma).
#include <cstdint>
#include <string>

#include "appearance/bsdf.h"

namespace svbrdf::testing {

struct Chi2Options {
  int samples = 100000;
  std::uint64_t seed = 1;
  int max_depth = 10;             // quadrant splits below the top grid
  double split_expected = 400;    // split a cell expected to hold more samples than this
  double min_expected = 5;        // pool bins until they expect at least this many
};

struct Chi2Result {
  double statistic = 0;
  int dof = 0;
  double p_value = 1;
  int bins = 0;                   // after pooling
  int leaves = 0;                 // before pooling
  double pdf_integral = 0;        // ∫ pdf over the sphere (quadrature)
  double finite_fraction = 0;     // observed fraction of finite samples
  std::string worst;              // the bin contributing most, for the failure message
};

Chi2Result chi2_test(const Bsdf& bsdf, const glm::vec3& wo, const Chi2Options& options = {});

// Q(k/2, x/2): the probability that a χ² variable with k degrees of freedom exceeds x.
double chi2_survival(double x, int dof);

}  // namespace svbrdf::testing
