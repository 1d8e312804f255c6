#include "render/alias_table.h"

#include <algorithm>

namespace svbrdf {

AliasTable::AliasTable(std::span<const float> weights) {
  const std::size_t n = weights.size();
  buckets_.resize(n);
  if (n == 0) return;
  double sum = 0.0;
  for (float w : weights) sum += w;
  // Each index's probability times n: a bucket is "small" below 1 (it has room for an alias).
  std::vector<double> scaled(n);
  std::vector<std::uint32_t> small, large;
  small.reserve(n);
  large.reserve(n);
  for (std::size_t k = 0; k < n; ++k) {
    scaled[k] = double(weights[k]) * double(n) / sum;
    (scaled[k] < 1.0 ? small : large).push_back(std::uint32_t(k));
  }
  // Vose: fill each small bucket from a large index, which shrinks by what it gave.
  while (!small.empty() && !large.empty()) {
    const std::uint32_t s = small.back(), l = large.back();
    small.pop_back();
    buckets_[s] = {float(scaled[s]), l};
    scaled[l] -= 1.0 - scaled[s];
    if (scaled[l] < 1.0) {
      large.pop_back();
      small.push_back(l);
    }
  }
  // What remains is 1 up to rounding: those buckets keep their own index.
  for (std::uint32_t k : small) buckets_[k] = {1.0f, k};
  for (std::uint32_t k : large) buckets_[k] = {1.0f, k};
}

std::size_t AliasTable::sample(float u_bucket, float u_choice, float& u_rest) const {
  constexpr float kBelowOne = 0x1.fffffep-1f;
  const std::size_t b = std::min(std::size_t(u_bucket * float(buckets_.size())), buckets_.size() - 1);
  const Bucket& bucket = buckets_[b];
  if (u_choice < bucket.keep) {
    u_rest = std::min(u_choice / bucket.keep, kBelowOne);
    return b;
  }
  u_rest = std::min((u_choice - bucket.keep) / (1.0f - bucket.keep), kBelowOne);
  return bucket.alias;
}

double AliasTable::probability(std::size_t k) const {
  const double n = double(buckets_.size());
  double p = double(buckets_[k].keep) / n;
  for (const Bucket& b : buckets_)
    if (b.alias == k && &b != &buckets_[k]) p += (1.0 - double(b.keep)) / n;
  return p;
}

}  // namespace svbrdf
