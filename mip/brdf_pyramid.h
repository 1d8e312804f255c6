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
// to what the file stores (stored_lobe.h: the file's codes, which the build and the MIP file use and a
// user of the pyramid does not need).
#include <cassert>
#include <cstdint>
#include <span>
#include <vector>

#include "base/huge_pages.h"
#include "mip/cache_lines.h"
#include "mip/coat_layer.h"
#include "mip/lobe.h"
#include "mip/lobe_reduction.h"
#include "mip/pyramid_shape.h"
#include "mip/radial_correction.h"
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
  // Whether some lobe of the level satisfies `has`.
  template <class Has>
  bool any_lobe(const Has& has) const {
    for (std::size_t t = 0; t < counts.size(); ++t)
      for (const Lobe& l : texel_lobes(t))
        if (has(l)) return true;
    return false;
  }
  // Whether some lobe has the specular layer's factors (ρ90 ≠ 0 or F90 ≠ 1: lobe.h), which the MIP file
  // then stores in kBytesPerSpecularLayer more bytes a slot.
  bool specular_layer() const {
    return any_lobe([](const Lobe& l) { return l.f90 != 1.0f || l.diffuse90 != glm::vec3(0.0f); });
  }
  // Whether some lobe has f0_tint ≠ 0 (a tintable pyramid of a material with metal), which the MIP file
  // then stores in kBytesPerTintLayer more bytes a slot.
  bool tint_layer() const { return any_lobe([](const Lobe& l) { return l.f0_tint != glm::vec3(0.0f); }); }
  // Whether some lobe is stretched (lobe.h, "Stretched shapes"), which the MIP file then stores in
  // kBytesPerStretch more bytes a slot.
  bool stretch_layer() const { return any_lobe([](const Lobe& l) { return l.stretch != 1.0f; }); }
  // Whether some lobe transmits (lobe.h "Transmission"), and whether some lobe's τ90 is not 0, which the
  // MIP file then stores in kBytesPerTransmission and kBytesPerTransmission90 more bytes a slot.
  bool transmission_layer() const { return any_lobe([](const Lobe& l) { return transmits(l); }); }
  bool transmission90_layer() const {
    return any_lobe([](const Lobe& l) { return l.transmission90 != glm::vec3(0.0f); });
  }
  // Whether some lobe's transmission is stretched (lobe.h "Transmission"), which the MIP file then
  // stores in kBytesPerTransmissionStretch more bytes a slot.
  bool transmission_stretch_layer() const { return any_lobe([](const Lobe& l) { return l.transmission_stretch != 1.0f; }); }
  // Whether some lobe transmits diffusely (diffuse_transmission.h), and whether some lobe's τd90 is not 0,
  // which the MIP file then stores in kBytesPerDiffuseTransmission and kBytesPerDiffuseTransmission90 more
  // bytes a slot.
  bool diffuse_transmission_layer() const {
    return any_lobe([](const Lobe& l) { return l.diffuse_transmission != glm::vec3(0.0f); });
  }
  bool diffuse_transmission90_layer() const {
    return any_lobe([](const Lobe& l) { return l.diffuse_transmission90 != glm::vec3(0.0f); });
  }
  // Makes room for `texels` texels, all empty.
  void reset(Extent e, std::size_t texels) {
    extent = e;
    counts.assign(texels, 0);
    assign_huge(single, texels, Lobe{});  // a 4096² material's level 1: 4 Mi lobes
    first.assign(texels, 0);
    lobes.clear();
  }
};

// The coat layer (coat_layer.h), for a material with KHR_materials_clearcoat: per level its coat
// lobes, stored as the base's are (a BrdfLevel; a texel without coat has none), and each base lobe's
// coat share (Lobe::coat). At most kCoatLobes coat lobes a texel (BrdfBuildOptions::coat_lobes); the
// MIP file stores per coat slot the weight, the normal's code and length deficit, α, the shape code and
// the skirt (stored_lobe.h's lobe without its colours, whose F0 = 0.04 and F90 = 1 the extension fixes),
// and per base slot the coat share as a half.
inline constexpr int kCoatLobes = kDefaultLobes;
inline constexpr int kBytesPerCoatLobe = 4 + 5 * 2;
inline constexpr int kBytesPerCoatShare = 2;

// The sheen (sheen_layer.h), for a material with KHR_materials_sheen: per level ≥ 1 the texels' sheen
// means (a SheenLayer each, which the MIP file stores once, as the parameter pyramid's) and each base
// lobe's sheen share (Lobe::sheen), which the MIP file stores as a half a base slot.
inline constexpr int kBytesPerSheenShare = 2;

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
  // Keep each lobe's f0_tint, so that the pyramid answers lookups under a tint of the base color
  // (glTF's COLOR_0; lobe.h tinted) at kBytesPerTintLayer a stored lobe. Without it f0_tint is 0 and
  // the pyramid is not tintable().
  bool tint = false;
  // The coat lobes a texel keeps at most (a material with a clear coat), up to kMaxLobes.
  int coat_lobes = kCoatLobes;
};

class BrdfPyramid {
 public:
  BrdfPyramid() = default;
  static BrdfPyramid build(const MaterialTexels& level0, const BrdfBuildOptions& options = {},
                           std::vector<BrdfLevelStats>* stats = nullptr);
  // From stored levels ≥ 1 (the MIP file), their radial corrections' grid (for levels whose
  // `correction` is not empty), the level-0 texels' extent, for a coated material the coat lobes
  // of levels ≥ 1 and for a material with a sheen the sheen means of every level (level 0's are not
  // kept); throws svbrdf::Error when the shapes do not form a pyramid.
  static BrdfPyramid from_levels(const MaterialTexels& level0, int max_lobes, std::vector<BrdfLevel> coarse,
                                 const RadialGrid& grid = {}, bool tintable = false, std::vector<BrdfLevel> coat = {},
                                 std::vector<std::vector<SheenLayer>> sheen = {});

  int levels() const { return static_cast<int>(levels_.size()); }
  Extent level0() const { return level0_; }
  Extent extent(int level) const { return levels_[static_cast<std::size_t>(level)].extent; }
  int max_lobes() const { return max_lobes_; }
  // Built with BrdfBuildOptions::tint: its lobes' f0_tint are kept, and tinted() of them is the tinted
  // texels' lobes.
  bool tintable() const { return tintable_; }
  const BrdfLevel& level(int level) const { return levels_[static_cast<std::size_t>(level)]; }

  // The lobes of texel (i, j) of `level` ≥ 1: a view into the pyramid, valid while it lives.
  std::span<const Lobe> texel(int level, int i, int j) const {
    assert(level >= 1);
    const BrdfLevel& l = levels_[static_cast<std::size_t>(level)];
    const std::size_t t = static_cast<std::size_t>(j) * l.extent.width + i;
    // The reads a texel may need are issued together: the count, the single slot, the index into the
    // packed lobes (the branch on the count would otherwise order them) and the radial correction.
    prefetch_reads(l, t);
    return l.texel_lobes(t);
  }
  // Asks the memory system for what texel(level, i, j) and coat(level, i, j) read first, for a caller
  // with other work to do before it reads them: the coat's reads are a second cache miss, which this
  // issues beside the base's instead of after them.
  void prefetch(int level, int i, int j) const {
    const BrdfLevel& l = levels_[static_cast<std::size_t>(level)];
    const std::size_t t = static_cast<std::size_t>(j) * l.extent.width + i;
    __builtin_prefetch(l.counts.data() + t);
    prefetch_reads(l, t);
    if (!sheen_.empty()) __builtin_prefetch(sheen_[static_cast<std::size_t>(level)].data() + t);
    if (coat_.empty()) return;
    const BrdfLevel& c = coat_[static_cast<std::size_t>(level)];
    __builtin_prefetch(c.counts.data() + t);
    prefetch_reads(c, t);
  }
  // Bytes per texel of a level as the MIP file stores it (fixed slots; memory holds fewer), the coat's
  // included; and the coat's alone.
  int bytes_per_texel(int level) const;
  int coat_bytes_per_texel(int level) const;
  // The sheen shares' bytes (the sheen means are the parameter pyramid's, ParamPyramid::kBytesPerSheenTexel).
  int sheen_bytes_per_texel(int level) const;
  // The radial correction of texel (i, j) of `level` ≥ 0, or null (below kFirstCorrectedLevel, level 0
  // included, or none built).
  const RadialCorrection* correction(int level, int i, int j) const {
    const BrdfLevel& l = levels_[static_cast<std::size_t>(level)];
    if (l.correction.empty()) return nullptr;
    return &l.correction[static_cast<std::size_t>(j) * l.extent.width + i];
  }
  const RadialGrid& radial_grid() const { return grid_; }

  // Whether the material has a clear coat, and the coat of texel (i, j) of `level` ≥ 1 (a view into the
  // pyramid, valid while it lives; no lobes for a material without a coat).
  bool has_coat() const { return !coat_.empty(); }
  CoatTexel coat(int level, int i, int j) const {
    assert(level >= 1);
    if (coat_.empty()) return {};
    const BrdfLevel& c = coat_[static_cast<std::size_t>(level)];
    return {c.texel_lobes(static_cast<std::size_t>(j) * c.extent.width + i)};
  }
  const BrdfLevel& coat_level(int level) const { return coat_[static_cast<std::size_t>(level)]; }

  // Whether the material has a sheen, and the sheen means of texel (i, j) of `level` ≥ 1 (sheen_layer.h).
  bool has_sheen() const { return !sheen_.empty(); }
  const SheenLayer& sheen(int level, int i, int j) const {
    assert(level >= 1);
    const std::vector<SheenLayer>& s = sheen_[static_cast<std::size_t>(level)];
    return s[static_cast<std::size_t>(j) * levels_[static_cast<std::size_t>(level)].extent.width + i];
  }
  std::span<const SheenLayer> sheen_level(int level) const { return sheen_[static_cast<std::size_t>(level)]; }

 private:
  // Texel t's single slot, its index into the packed lobes and its radial correction.
  static void prefetch_reads(const BrdfLevel& l, std::size_t t) {
    prefetch_object(l.single.data() + t);
    __builtin_prefetch(l.first.data() + t);
    if (!l.correction.empty()) prefetch_object(l.correction.data() + t);
  }

  Extent level0_{};
  int max_lobes_ = 1;
  bool tintable_ = false;
  RadialGrid grid_{};
  std::vector<BrdfLevel> levels_;
  std::vector<BrdfLevel> coat_;  // the coat lobes per level (level 0's empty), or none without a coat
  std::vector<std::vector<SheenLayer>> sheen_;  // the sheen means per level (level 0's empty), or none
};

}  // namespace svbrdf
