#pragma once
// The BRDF pyramid (../shared/spec/brdf-mip.md, `brdf`): every texel of every level a small mixture of
// lobes (lobe.h) whose BRDF approximates F_L,ij, the mean of the covered level-0 texels' f_eff.
//
// Level 0 is one lobe per texel, exactly f_eff: the level-0 texels themselves (level0_lobe), which the
// pyramid does not hold a second time (brdf_texel in mip_data.h answers for any level). Level L is
// built from level L − 1 only: a texel's children's lobes, their weights scaled by the children's
// shares of its area, form the exact union (the mean of the children's mixtures), which
// lobe_reduction.h reduces to at most `max_lobes` lobes. The build is O(texels) and parallel over
// bands of rows (oneTBB).
//
// Storage: per level the texels' lobes packed one texel after another (a texel of smooth material
// keeps one lobe, so fixed slots would waste three quarters of a level at K = 4), with each texel's
// first lobe and count. `slots` is the most lobes any texel of the level kept: the MIP file's fixed
// slots. The lobes are rounded to what the file stores (round_to_stored).
#include <cassert>
#include <cstdint>
#include <span>
#include <vector>

#include "mip/lobe.h"
#include "mip/lobe_reduction.h"
#include "mip/pyramid_shape.h"
#include "textures/material_texels.h"

namespace svbrdf {

struct BrdfLevel {
  Extent extent{};
  int slots = 1;                      // the most lobes a texel has
  std::vector<Lobe> lobes;            // every texel's lobes, in row-major texel order
  std::vector<std::uint32_t> first;   // per texel: its first lobe in `lobes`
  std::vector<std::uint8_t> counts;   // per texel: its lobe count
};

// What the build measured, per level: the mean and max lobe count, and the reduction error (e_rel of
// the reduced mixture against the exact union of its children's lobes, on the metric's 4225 pairs)
// over a sample of texels.
struct BrdfLevelStats {
  double mean_lobes = 0;
  int max_lobes = 0;
  double reduction_erel_mean = 0;
  double reduction_erel_max = 0;
  int sampled = 0;
};

struct BrdfBuildOptions {
  ReductionOptions reduction{};
  int stats_samples = 0;  // texels per level whose reduction error is measured (0: none)
};

// A lobe's shape (lobe.h) in one number: ln(alpha2_hi/alpha2) > 0 for a roughness mixture, −μ ∈ [−1, 0]
// for a GGX core with a Beckmann share μ (−1: plain GGX). The two kinds never mix (a roughness mixture
// has μ = 1), so one channel of the MIP file holds either, as a half float: 5e-4 relative on μ, and on
// the mixture's span, which moves its tail and peak moments by less than that. Mixtures spanning less
// than 0.1 % of α² store as plain GGX (lobe_shape treats them so below 0.01 %).
float lobe_shape_code(const Lobe& lobe);
void set_lobe_shape_code(Lobe& lobe, float code);

// Rounds a lobe to what the MIP file stores: weight, colors and shape code as half floats, normal and
// α² as 32-bit floats. The BRDF pyramid holds its lobes so rounded, which is what makes the file's
// round trip bit-identical and what its figures measure.
void round_to_stored(Lobe& lobe);

// Bytes a stored lobe takes: normal (3) and α² as 32-bit floats; weight, ρ (3), F0 (3) and the shape
// code as half floats.
inline constexpr int kBytesPerLobe = 4 * 4 + 8 * 2;

class BrdfPyramid {
 public:
  BrdfPyramid() = default;
  static BrdfPyramid build(const MaterialTexels& level0, const BrdfBuildOptions& options = {},
                           std::vector<BrdfLevelStats>* stats = nullptr);
  // From stored levels ≥ 1 (the MIP file) and the level-0 texels' extent; throws svbrdf::Error when
  // the shapes do not form a pyramid.
  static BrdfPyramid from_levels(const MaterialTexels& level0, int max_lobes, std::vector<BrdfLevel> coarse);

  int levels() const { return static_cast<int>(levels_.size()); }
  Extent level0() const { return level0_; }
  Extent extent(int level) const { return levels_[static_cast<std::size_t>(level)].extent; }
  int max_lobes() const { return max_lobes_; }
  const BrdfLevel& level(int level) const { return levels_[static_cast<std::size_t>(level)]; }

  // The lobes of texel (i, j) of `level` ≥ 1: a view into the pyramid, valid while it lives.
  std::span<const Lobe> texel(int level, int i, int j) const {
    assert(level >= 1);
    const BrdfLevel& l = levels_[static_cast<std::size_t>(level)];
    const std::size_t t = static_cast<std::size_t>(j) * l.extent.width + i;
    return {l.lobes.data() + l.first[t], l.counts[t]};
  }
  // Asks the memory system for what texel(level, i, j) reads first (its lobe index and count), for
  // a caller with other work to do before it reads them.
  void prefetch(int level, int i, int j) const {
    const BrdfLevel& l = levels_[static_cast<std::size_t>(level)];
    const std::size_t t = static_cast<std::size_t>(j) * l.extent.width + i;
    __builtin_prefetch(l.first.data() + t);
    __builtin_prefetch(l.counts.data() + t);
  }
  // Bytes per texel of a level as the MIP file stores it (fixed slots; memory holds fewer).
  int bytes_per_texel(int level) const { return this->level(level).slots * kBytesPerLobe; }

 private:
  Extent level0_{};
  int max_lobes_ = 1;
  std::vector<BrdfLevel> levels_;
};

}  // namespace svbrdf
