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
// Storage: per level, a texel with one lobe (most: smooth material keeps one) holds it in its own slot
// of `single`, which a lookup reads with no indirection; the lobes of texels with more are packed
// one texel after another in `lobes` (fixed slots of K would waste most of a level at K = 4), with
// each texel's first lobe there, and every texel's count. A lookup thus waits for one memory access
// where the packed layout alone made it wait for two in a row (the index, then the lobes). `slots`
// is the most lobes any texel of the level kept: the MIP file's fixed slots. The lobes are rounded
// to what the file stores (round_to_stored).
#include <cassert>
#include <cstdint>
#include <span>
#include <vector>

#include "mip/lobe.h"
#include "mip/lobe_reduction.h"
#include "mip/pyramid_shape.h"
#include "mip/radial_correction.h"
#include "mip/stored_normal.h"
#include "textures/material_texels.h"

namespace svbrdf {

struct BrdfLevel {
  Extent extent{};
  int slots = 1;                      // the most lobes a texel has
  std::vector<std::uint8_t> counts;   // per texel: its lobe count
  std::vector<Lobe> single;           // per texel: its lobe, when it has exactly one
  std::vector<Lobe> lobes;            // the lobes of texels with two or more, in row-major texel order
  std::vector<std::uint32_t> first;   // per texel: where its lobes start in `lobes` (texels with ≥ 2)
  std::vector<RadialCorrection> correction;  // per texel from kFirstCorrectedLevel on (radial_correction.h), else empty

  // Texel t's lobes: a view into the level (writable for the build's re-centring).
  std::span<Lobe> texel_lobes(std::size_t t) {
    const int n = counts[t];
    return n == 1 ? std::span<Lobe>(&single[t], 1) : std::span<Lobe>(lobes.data() + first[t], static_cast<std::size_t>(n));
  }
  std::span<const Lobe> texel_lobes(std::size_t t) const { return const_cast<BrdfLevel*>(this)->texel_lobes(t); }
  // Every texel's lobes in texel order (a copy: for comparisons, not for lookups).
  std::vector<Lobe> all_lobes() const {
    std::vector<Lobe> out;
    for (std::size_t t = 0; t < counts.size(); ++t) {
      const std::span<const Lobe> l = texel_lobes(t);
      out.insert(out.end(), l.begin(), l.end());
    }
    return out;
  }
  // Makes room for `texels` texels, all empty.
  void reset(Extent e, std::size_t texels) {
    extent = e;
    counts.assign(texels, 0);
    single.assign(texels, Lobe{});
    first.assign(texels, 0);
    lobes.clear();
  }
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
  bool radial_correction = true;  // radial_correction.h, from kFirstCorrectedLevel on
  bool recentre = true;           // and the lobes re-centred before it (radial_correction.h)
  int stats_samples = 0;  // texels per level whose reduction error is measured (0: none)
};

// A lobe's shape (lobe.h) in two numbers, the MIP file's shape and skirt channels, as half floats.
// The shape code: ln(alpha2_hi/alpha2) > 0 for a roughness mixture whose upper part is the band,
// −(1 + ln(alpha2_hi/alpha2)) < −1 for one whose upper part is an atom (a two-point mixture), −μ ∈ [−1, 0]
// for a spread core with GGX share μ (−1: plain GGX): 5e-4 relative on μ and on the mixture's span,
// which moves its tail and peak moments by less than that. Mixtures spanning less than 0.1 % of α²
// store as plain GGX (lobe_shape treats them so below 0.01 %). set_lobe_shape_code sets alpha2_hi, the
// mixture's kind (skirt 1 or 0) or the core's μ (ggx).
float lobe_shape_code(const Lobe& lobe);
void set_lobe_shape_code(Lobe& lobe, float code);
// The skirt code: a spread core's c ≥ 1; a roughness mixture's upper share β, two-sided — β itself up
// to ½, β − 1 ∈ (−½, 0] above — so that a half keeps 5e-4 relative on the smaller of β and 1 − β (both
// shares carry moments: the atom the peak, the upper part the tail); 1 for plain GGX.
// set_lobe_skirt_code needs the lobe's shape code set first (it tells a mixture from a core).
float lobe_skirt_code(const Lobe& lobe);
void set_lobe_skirt_code(Lobe& lobe, float code);

// Rounds a lobe to what the MIP file stores: weight, colors, α (the square root of alpha2), shape code
// and skirt as half floats, the normal as stored_normal.h codes it. The BRDF pyramid holds its lobes so
// rounded, which is what makes the file's round trip bit-identical and what its figures measure.
void round_to_stored(Lobe& lobe);

// Bytes a stored lobe takes: the normal's direction as a 32-bit code (stored_normal.h); weight, ρ (3),
// F0 (3), the normal's length deficit, α, the shape code and the skirt as half floats.
inline constexpr int kBytesPerLobe = 4 + 11 * 2;

class BrdfPyramid {
 public:
  BrdfPyramid() = default;
  static BrdfPyramid build(const MaterialTexels& level0, const BrdfBuildOptions& options = {},
                           std::vector<BrdfLevelStats>* stats = nullptr);
  // From stored levels ≥ 1 (the MIP file), their radial corrections' grid (for levels whose
  // `correction` is not empty) and the level-0 texels' extent; throws svbrdf::Error when the shapes do
  // not form a pyramid.
  static BrdfPyramid from_levels(const MaterialTexels& level0, int max_lobes, std::vector<BrdfLevel> coarse,
                                 const RadialGrid& grid = {});

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
    // The reads a texel may need are issued together: the count, the single slot, the index into the
    // packed lobes (the branch on the count would otherwise order them) and the radial correction.
    prefetch_single(l, t);
    __builtin_prefetch(l.first.data() + t);
    prefetch_correction(l, t);
    return l.texel_lobes(t);
  }
  // Asks the memory system for what texel(level, i, j) reads first, for a caller with other work to
  // do before it reads them.
  void prefetch(int level, int i, int j) const {
    const BrdfLevel& l = levels_[static_cast<std::size_t>(level)];
    const std::size_t t = static_cast<std::size_t>(j) * l.extent.width + i;
    __builtin_prefetch(l.counts.data() + t);
    prefetch_single(l, t);
    __builtin_prefetch(l.first.data() + t);
    prefetch_correction(l, t);
  }
  // Bytes per texel of a level as the MIP file stores it (fixed slots; memory holds fewer).
  int bytes_per_texel(int level) const {
    const BrdfLevel& l = this->level(level);
    return l.slots * kBytesPerLobe + (l.correction.empty() ? 0 : kBytesPerCorrection);
  }
  // The radial correction of texel (i, j) of `level` ≥ 0, or null (below kFirstCorrectedLevel, level 0
  // included, or none built).
  const RadialCorrection* correction(int level, int i, int j) const {
    const BrdfLevel& l = levels_[static_cast<std::size_t>(level)];
    if (l.correction.empty()) return nullptr;
    return &l.correction[static_cast<std::size_t>(j) * l.extent.width + i];
  }
  const RadialGrid& radial_grid() const { return grid_; }

 private:
  // The radial corrections of the levels from kFirstCorrectedLevel on (radial_correction.h).
  void build_corrections(const MaterialTexels& level0, bool recentre);
  // A texel's correction (48 B) may straddle two cache lines: both are asked for.
  static void prefetch_correction(const BrdfLevel& l, std::size_t t) {
    if (l.correction.empty()) return;
    const char* p = reinterpret_cast<const char*>(l.correction.data() + t);
    __builtin_prefetch(p);
    __builtin_prefetch(p + sizeof(RadialCorrection) - 1);
  }
  // A Lobe may straddle two cache lines: both are asked for.
  static void prefetch_single(const BrdfLevel& l, std::size_t t) {
    const char* p = reinterpret_cast<const char*>(l.single.data() + t);
    __builtin_prefetch(p);
    __builtin_prefetch(p + sizeof(Lobe) - 1);
  }

  Extent level0_{};
  int max_lobes_ = 1;
  RadialGrid grid_{};
  std::vector<BrdfLevel> levels_;
};

}  // namespace svbrdf
