// render/alias_table.h: the table draws each index with its weight's share, and the uniform it hands
// back is uniform whichever index was drawn.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "appearance/rng.h"
#include "render/alias_table.h"

namespace svbrdf {
namespace {

std::vector<float> skewed_weights() {
  // Zeros, a dominant entry, many small ones: every case of Vose's construction.
  std::vector<float> w(37);
  for (std::size_t k = 0; k < w.size(); ++k) w[k] = float((k * 7) % 5);
  w[11] = 90.0f;
  w[36] = 0.001f;
  return w;
}

// The probabilities the table encodes (its buckets' shares, read back) are the weights' shares.
TEST(AliasTable, EncodesTheWeightsShares) {
  const std::vector<float> w = skewed_weights();
  double sum = 0.0;
  for (float x : w) sum += x;
  const AliasTable t(w);
  ASSERT_EQ(t.size(), w.size());
  double total = 0.0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    EXPECT_NEAR(t.probability(k), w[k] / sum, 1e-6) << "index " << k;
    total += t.probability(k);
  }
  EXPECT_NEAR(total, 1.0, 1e-6);
}

// Drawing: frequencies within 4 standard deviations of the shares (a property of the sampler, not of
// the table), zero weights never drawn, and u_rest uniform (mean ½, variance 1/12) for a given index.
TEST(AliasTable, DrawsInProportionWithAUniformRest) {
  const std::vector<float> w = skewed_weights();
  double sum = 0.0;
  for (float x : w) sum += x;
  const AliasTable t(w);
  Rng rng(3, 9);
  const int n = 400000;
  std::vector<int> count(w.size(), 0);
  double rest_sum = 0.0, rest_sq = 0.0;
  int rest_n = 0;
  for (int i = 0; i < n; ++i) {
    float rest = -1.0f;
    const std::size_t k = t.sample(rng.next_float(), rng.next_float(), rest);
    ASSERT_LT(k, w.size());
    ASSERT_GE(rest, 0.0f);
    ASSERT_LT(rest, 1.0f);
    ++count[k];
    if (k == 11) rest_sum += rest, rest_sq += double(rest) * rest, ++rest_n;
  }
  for (std::size_t k = 0; k < w.size(); ++k) {
    const double p = w[k] / sum, sd = std::sqrt(n * p * (1 - p));
    if (w[k] == 0.0f) EXPECT_EQ(count[k], 0) << "index " << k;
    else EXPECT_NEAR(count[k], n * p, 4 * sd + 1) << "index " << k;
  }
  const double mean = rest_sum / rest_n, var = rest_sq / rest_n - mean * mean;
  EXPECT_NEAR(mean, 0.5, 4 * std::sqrt(1.0 / 12 / rest_n));
  EXPECT_NEAR(var, 1.0 / 12, 0.002);
}

}  // namespace
}  // namespace svbrdf
