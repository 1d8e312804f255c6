#pragma once
// Random numbers for sampling: PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient
// Statistically Good Algorithms"), seeded per pixel and sample so that results never depend on
// which thread ran what (DESIGN.md, "Conventions").
#include <cstdint>

namespace svbrdf {

class Rng {
 public:
  Rng() : Rng(0x853c49e6748fea9bULL, 0xda3e39cb94b95bdbULL) {}
  Rng(std::uint64_t seed, std::uint64_t stream) { seed_stream(seed, stream); }

  void seed_stream(std::uint64_t seed, std::uint64_t stream) {
    state_ = 0;
    inc_ = (stream << 1u) | 1u;
    next_u32();
    state_ += seed;
    next_u32();
  }

  std::uint32_t next_u32() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ULL + inc_;
    const auto xorshifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<std::uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((32u - rot) & 31u));
  }

  // 64 random bits: the first draw in the high word. Two statements, since the operands of one
  // expression are unsequenced and the order would be the compiler's.
  std::uint64_t next_u64() {
    const std::uint64_t hi = next_u32();
    return (hi << 32) | next_u32();
  }
  // Uniform in [0, 1): 24 random bits, so 1 is never returned.
  float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1p-24f; }
  // Uniform in [0, 1) with 53 random bits.
  double next_double() {
    const std::uint64_t hi = next_u32() >> 5, lo = next_u32() >> 6;
    return static_cast<double>((hi << 26) | lo) * 0x1p-53;
  }

 private:
  std::uint64_t state_ = 0, inc_ = 1;
};

// A 64-bit mix (SplitMix64 finalizer, Steele et al. 2014) to derive independent seeds from
// (pixel, sample) coordinates.
inline std::uint64_t mix64(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace svbrdf
