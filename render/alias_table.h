#pragma once
// Drawing an index with probability proportional to given weights in constant time: Walker's alias
// method, built by Vose's algorithm (M. D. Vose, "A linear algorithm for generating random numbers
// with a given distribution", IEEE TSE 17(9), 1991). Each of the n buckets holds the share `keep` of
// its own index and sends the rest to one `alias`; a draw picks a bucket and then one of its two
// indices — two loads, where a CDF's bisection takes log2(n) dependent ones (the environment's
// importance sampling, lights.h).
#include <cstdint>
#include <span>
#include <vector>

namespace svbrdf {

class AliasTable {
 public:
  AliasTable() = default;
  // Weights ≥ 0, finite, with a positive sum (the caller checks); at most 2^32 − 1 of them.
  explicit AliasTable(std::span<const float> weights);

  std::size_t size() const { return buckets_.size(); }

  // The index drawn by two independent uniforms on [0, 1): u_bucket picks the bucket, u_choice one of
  // its two indices (two numbers rather than the fractional part of one, which keeps no bits for the
  // choice once n nears float's 2^24). `u_rest` receives u_choice rescaled within the part it fell in:
  // uniform on [0, 1) and independent of the index drawn.
  std::size_t sample(float u_bucket, float u_choice, float& u_rest) const;

  // The probability with which sample() draws index k, from the table itself (for tests).
  double probability(std::size_t k) const;

 private:
  struct Bucket {
    float keep = 1.0f;       // probability that the bucket's own index is drawn
    std::uint32_t alias = 0;  // the index drawn otherwise
  };
  std::vector<Bucket> buckets_;
};

}  // namespace svbrdf
