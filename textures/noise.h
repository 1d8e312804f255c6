#pragma once
// Counter-based randomness and periodic noise for the procedural material families. Everything is
// a pure function of (seed, integer coordinates), so a texel's value never depends on which thread
// computed it or in which order: bakes are byte-identical for a seed at any thread count.
// Noise is periodic over the texture (a lattice of `cells` cells across it), so texture sets tile.
#include <cstdint>

#include <glm/glm.hpp>

namespace svbrdf::noise {

// SplitMix64's finalizer (Steele, Lea and Flood 2014, "Fast splittable pseudorandom number
// generators"): a bijective 64-bit mix with full avalanche.
constexpr std::uint64_t mix(std::uint64_t z) {
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

// One finalizer over a linear combination of the coordinates with odd 64-bit multipliers: distinct
// small coordinates never collide, and the finalizer's avalanche decorrelates neighbours. The
// seed goes through its own mix so nearby seeds give unrelated fields.
constexpr std::uint64_t hash(std::uint64_t seed, std::int64_t a, std::int64_t b = 0, std::int64_t c = 0) {
  return mix(mix(seed) ^ (static_cast<std::uint64_t>(a) * 0xd1b54a32d192ed03ULL +
                          static_cast<std::uint64_t>(b) * 0xaef17502108ef2d9ULL +
                          static_cast<std::uint64_t>(c) * 0xf1357aea2e62a9c5ULL));
}

// Uniform in [0, 1) from the top 24 bits (exact in float).
constexpr float unit(std::uint64_t h) { return static_cast<float>(h >> 40) * 0x1p-24f; }
constexpr float unit(std::uint64_t seed, std::int64_t a, std::int64_t b = 0, std::int64_t c = 0) {
  return unit(hash(seed, a, b, c));
}

// A sequence of uniform numbers from a counter: for placing a few features serially.
class Sequence {
 public:
  Sequence(std::uint64_t seed, std::uint64_t stream) : seed_(hash(seed, static_cast<std::int64_t>(stream), 0x5e9)) {}
  float uniform() { return unit(seed_, counter_++); }
  float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }

 private:
  std::uint64_t seed_;
  std::int64_t counter_ = 0;
};

// 2D gradient noise (Perlin 2002, "Improving noise": quintic fade, gradients at lattice points),
// on a lattice periodic with (period_x, period_y) cells; (x, y) in lattice units. Range about
// [−0.7, 0.7], mean 0, zero at lattice points.
float gradient(std::uint64_t seed, double x, double y, int period_x, int period_y);

// 1D gradient noise, periodic with `period` cells.
float gradient1(std::uint64_t seed, double x, int period);

// Fractal sum over octaves on texture coordinates (u, v) ∈ [0, 1)²: octave k uses cells·2^k
// cells across the texture and amplitude gain^k; normalized so the result's range is about [−1, 1].
float fbm(std::uint64_t seed, double u, double v, int cells, int octaves, float gain = 0.5f);

// Jittered-grid cellular noise (Worley 1996, "A cellular texture basis function"), periodic with
// cells × cells cells over the texture. Distances are in cell units.
struct CellularHit {
  float f1 = 0, f2 = 0;           // distances to the nearest and second-nearest feature points
  int cell_x = 0, cell_y = 0;     // the nearest feature's cell (wrapped into [0, cells))
  glm::vec2 to_nearest{0.0f};     // vector from (u, v) to the nearest feature, cell units
};
CellularHit cellular(std::uint64_t seed, double u, double v, int cells, float jitter = 0.9f);

// The number of lattice cells across a texture of length_mm so that cells are about feature_mm
// wide (at least 1): noise features keep their physical size whatever the texture size.
int cells_for(double length_mm, double feature_mm);

// Smooth Hermite step, as GLSL's smoothstep.
inline float smoothstep(float e0, float e1, float x) {
  const float t = glm::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

}  // namespace svbrdf::noise
