// The thin-walled transmission of the BRDF pyramid (mip/lobe.h "Transmission"): a coarse texel's lobes
// transmit through their members' lobes untilted (one GGX of their peak), with the transmission's
// factors averaged by the merges and scaled to keep the union's transmitted flux. Against the exact reference (the mean of the covered texels' BTDFs), at every level ≥ 1
// of random-family materials (textures/random_material.h) given a transmission texture, the
// transmitted radiance's log error and flux are held to the reflected radiance's at the mirrored pairs.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "appearance/rng.h"
#include "mip/exact_reference.h"
#include "mip/lobe_mixture_bsdf.h"
#include "mip/mip_data.h"
#include "textures/random_material.h"

namespace svbrdf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The metric's directions (../shared/spec/brdf-mip.md) at every other polar angle: θ ∈ {0°, 20°, …, 80°}
// × φ ∈ {0°, 45°, …, 315°}, θ = 0 once.
std::vector<glm::dvec3> directions() {
  std::vector<glm::dvec3> d{{0, 0, 1}};
  for (int t = 20; t <= 80; t += 20)
    for (int p = 0; p < 360; p += 45) {
      const double th = t * kPi / 180, ph = p * kPi / 180;
      d.push_back({std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)});
    }
  return d;
}

// A random-family material given a transmission texture: 4 × 4-texel patches that transmit nothing or
// U[0.3, 1] of the dielectric base (a print on a clear film), from the seed's own stream.
MaterialTexels transmitting(std::uint64_t seed, int size) {
  MaterialTexels m = random_material_texels(draw_random_material(seed), size);
  Rng rng(seed, 11);
  std::vector<float> patch(std::size_t(size / 4) * (size / 4));
  for (float& t : patch) t = rng.next_float() < 0.3f ? 0.0f : 0.3f + 0.7f * rng.next_float();
  m.transmission_factor = 1.0f;
  m.transmission.resize(m.size());
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) m.transmission[m.index(i, j)] = patch[std::size_t(j / 4) * (size / 4) + i / 4];
  return m;
}

// One side's figures at a level: e_log over the pairs, channels and texels measured (L = F·|wi.z|), and
// the flux Σ L̂ / Σ L − 1 over the same.
struct Side {
  double sq = 0, n = 0, got = 0, want = 0;
  void add(const glm::dvec3& f_got, const glm::dvec3& f_want, double cos_i) {
    for (int c = 0; c < 3; ++c) {
      const double a = f_got[c] * cos_i, b = f_want[c] * cos_i;
      const double d = std::log1p(a) - std::log1p(b);
      sq += d * d, n += 1, got += a, want += b;
    }
  }
  double elog() const { return std::sqrt(sq / n); }
  double flux() const { return got / want - 1; }
};

TEST(TransmissionPyramid, TransmitsAsWellAsItReflects) {
  const std::vector<glm::dvec3> dirs = directions();
  for (const std::uint64_t seed : {3u, 8u, 21u}) {
    const MaterialTexels texels = transmitting(seed, 16);
    const MipData mip = build_mip(texels);
    const ExactReference exact(mip.level0);
    for (int level = 1; level < mip.levels(); ++level) {
      SCOPED_TRACE("seed " + std::to_string(seed) + " level " + std::to_string(level));
      const Extent e = mip.extent(level);
      Side reflected, transmitted;
      for (int j = 0; j < e.height; j += std::max(1, e.height / 4))
        for (int i = 0; i < e.width; i += std::max(1, e.width / 4)) {
          Lobe scratch, coat_scratch;
          LobeMixtureBsdf b(brdf_texel(mip, level, i, j, scratch), brdf_coat(mip, level, i, j, coat_scratch).lobes);
          if (const SheenLayer* s = brdf_sheen(mip, level, i, j)) b.set_sheen(*s);
          for (const glm::dvec3& wi : dirs)
            for (const glm::dvec3& wo : dirs) {
              const glm::dvec3 below(wi.x, wi.y, -wi.z);
              reflected.add(glm::dvec3(b.eval(glm::vec3(wi), glm::vec3(wo))), exact.eval(level, i, j, wi, wo), wi.z);
              transmitted.add(glm::dvec3(b.eval(glm::vec3(below), glm::vec3(wo))), exact.eval(level, i, j, below, wo), wi.z);
            }
        }
      std::printf("seed %2llu level %d  e_log reflected %.4f transmitted %.4f  flux reflected %+.2f %% transmitted %+.2f %%\n",
                  static_cast<unsigned long long>(seed), level, reflected.elog(), transmitted.elog(),
                  100 * reflected.flux(), 100 * transmitted.flux());
      // The transmission is carried as well as the reflection, to a margin: e_log within the reflection's
      // + 0.01 and the flux over the pairs within its + 3 points (the worst of these seeds: +0.004 and
      // +2.0 points, seed 3 level 3). Lobes transmitting through their reflection's shape (widened by
      // their normals' spread) made e_log 0.2–0.7 and lost 60–80 % of the flux at level ≥ 2; the
      // transmission's own shape with the reflection's flux factor was 5–44 % bright.
      ASSERT_GT(transmitted.want, 0.0);
      EXPECT_LE(transmitted.elog(), reflected.elog() + 0.01);
      EXPECT_LE(std::abs(transmitted.flux()), std::abs(reflected.flux()) + 0.03);
    }
  }
}

}  // namespace
}  // namespace svbrdf
