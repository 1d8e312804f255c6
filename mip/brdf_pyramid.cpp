#include "mip/brdf_pyramid.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "appearance/gltf.h"
#include "appearance/rng.h"
#include "base/error.h"
#include "mip/direction_grid.h"
#include "mip/exact_reference.h"
#include "mip/param_pyramid.h"
#include "mip/sheen_layer.h"
#include "mip/stored_lobe.h"
#include "mip/stored_normal.h"

namespace svbrdf {

namespace {

// Level 0's entry: its extent only (its lobes are the level-0 texels').
BrdfLevel level_zero(Extent e) {
  BrdfLevel l;
  l.extent = e;
  l.slots = 1;
  return l;
}

constexpr int kUnionCap = 9 * kMaxLobes;

// The union of texel (i, j)'s children's lobes, weights scaled by the children's area shares; the
// children are `fine`'s texels, or at level 1 the level-0 texels m (their base lobes, or with `coat`
// their coat lobes).
int gather_children(Extent level0, int level, int i, int j, const BrdfLevel& fine, const MaterialTexels& m,
                    std::array<Lobe, kUnionCap>& out, bool coat = false) {
  const Span cx = child_span(level0.width, level, i), cy = child_span(level0.height, level, j);
  const double total = static_cast<double>(level0_span(level0.width, level, i).size()) *
                       level0_span(level0.height, level, j).size();
  int n = 0;
  for (int y = cy.begin; y < cy.end; ++y)
    for (int x = cx.begin; x < cx.end; ++x) {
      const double share = static_cast<double>(level0_span(level0.width, level - 1, x).size()) *
                           level0_span(level0.height, level - 1, y).size() / total;
      const std::size_t t = static_cast<std::size_t>(y) * fine.extent.width + x;
      if (level == 1 && coat) {
        out[static_cast<std::size_t>(n++)] = coat_lobe(m.coat_layer(t), static_cast<float>(share));
        continue;
      }
      if (level == 1) {
        Lobe& l = out[static_cast<std::size_t>(n++)];
        l = level0_lobe(m, t);
        l.weight = static_cast<float>(share);
        continue;
      }
      for (Lobe l : fine.texel_lobes(t)) {
        l.weight = static_cast<float>(l.weight * share);
        out[static_cast<std::size_t>(n++)] = l;
      }
    }
  return n;
}

double table_erel(const BrdfTable& approx, const BrdfTable& ref) {
  const DirectionGrid& g = DirectionGrid::get();
  double num = 0, den = 0;
  for (int p = 0; p < DirectionGrid::kPairs; ++p) {
    const double cz = g.direction(DirectionGrid::wi_index(p)).z;
    const glm::dvec3 d = (approx[static_cast<std::size_t>(p)] - ref[static_cast<std::size_t>(p)]) * cz;
    const glm::dvec3 r = ref[static_cast<std::size_t>(p)] * cz;
    num += glm::dot(d, d);
    den += glm::dot(r, r);
  }
  return den > 0 ? std::sqrt(num / den) : 0.0;
}

BrdfLevel level_from_below(Extent level0, int level, const BrdfLevel& fine, const MaterialTexels& m,
                           const BrdfBuildOptions& options, BrdfLevelStats* stats, bool coat = false) {
  const Extent e = level_extent(level0, level);
  ReductionOptions reduction = options.reduction;
  if (coat) reduction.max_lobes = options.coat_lobes;
  const int max_lobes = std::clamp(reduction.max_lobes, 1, kMaxLobes);
  BrdfLevel out;
  const std::size_t texels = static_cast<std::size_t>(e.width) * e.height;
  out.reset(e, texels);
  // Bands of rows reduce in parallel into their own packed lists, joined in row order after.
  constexpr int kBandRows = 8;
  const int bands = (e.height + kBandRows - 1) / kBandRows;
  std::vector<std::vector<Lobe>> band_lobes(static_cast<std::size_t>(bands));
  tbb::parallel_for(0, bands, [&](int b) {
    std::array<Lobe, kUnionCap> buf;
    std::vector<Lobe>& packed = band_lobes[static_cast<std::size_t>(b)];
    packed.reserve(static_cast<std::size_t>(e.width) * kBandRows * 2);
    for (int j = b * kBandRows; j < std::min(e.height, (b + 1) * kBandRows); ++j)
      for (int i = 0; i < e.width; ++i) {
        const int n = gather_children(level0, level, i, j, fine, m, buf, coat);
        const int reduced = reduce_lobes(buf, n, reduction);
        const std::size_t t = static_cast<std::size_t>(j) * e.width + i;
        int kept = 0;
        for (int k = 0; k < std::min(reduced, max_lobes); ++k) {
          Lobe& l = buf[static_cast<std::size_t>(k)];
          if (!options.tint) l.f0_tint = glm::vec3(0.0f);
          if (coat) round_coat_lobe_to_stored(l);
          else round_to_stored(l);
          // A lobe below a half float's smallest weight (6e-8 of the texel) is dropped: the file
          // could not tell it from an empty slot.
          if (l.weight > 0) buf[static_cast<std::size_t>(kept++)] = l;
        }
        out.counts[t] = static_cast<std::uint8_t>(kept);
        out.first[t] = static_cast<std::uint32_t>(packed.size());  // within the band
        if (kept == 1) out.single[t] = buf[0];
        else packed.insert(packed.end(), buf.begin(), buf.begin() + kept);
      }
  });
  std::size_t total = 0;
  for (const auto& b : band_lobes) total += b.size();
  out.lobes.reserve(total);
  for (int b = 0; b < bands; ++b) {
    const std::uint32_t base = static_cast<std::uint32_t>(out.lobes.size());
    for (int j = b * kBandRows; j < std::min(e.height, (b + 1) * kBandRows); ++j)
      for (int i = 0; i < e.width; ++i) out.first[static_cast<std::size_t>(j) * e.width + i] += base;
    const auto& bl = band_lobes[static_cast<std::size_t>(b)];
    out.lobes.insert(out.lobes.end(), bl.begin(), bl.end());
    std::vector<Lobe>().swap(band_lobes[static_cast<std::size_t>(b)]);
  }
  int slots = 1;
  double sum = 0;
  for (std::uint8_t c : out.counts) slots = std::max<int>(slots, c), sum += c;
  out.slots = slots;
  if (stats && !coat) {
    stats->mean_lobes = sum / static_cast<double>(texels);
    stats->max_lobes = slots;
    // The reduction error measured against the exact union, on a fixed random sample of texels.
    const int samples = std::min<long long>(options.stats_samples, static_cast<long long>(texels));
    if (samples > 0) {
      std::vector<double> errs(static_cast<std::size_t>(samples));
      tbb::parallel_for(0, samples, [&](int s) {
        Rng rng(mix64(static_cast<std::uint64_t>(level) * 7919 + static_cast<std::uint64_t>(s)), 5);
        const std::size_t t = std::min<std::size_t>(texels - 1, static_cast<std::size_t>(rng.next_double() * texels));
        const int i = static_cast<int>(t % e.width), j = static_cast<int>(t / e.width);
        std::array<Lobe, kUnionCap> buf;
        const int n = gather_children(level0, level, i, j, fine, m, buf);
        BrdfTable ref = make_table(), approx = make_table();
        for (int k = 0; k < n; ++k) accumulate_lobe_double(buf[static_cast<std::size_t>(k)], 1.0, ref);
        for (const Lobe& l : out.texel_lobes(t)) accumulate_lobe_double(l, 1.0, approx);
        errs[static_cast<std::size_t>(s)] = table_erel(approx, ref);
      });
      double m = 0, mx = 0;
      for (double x : errs) m += x, mx = std::max(mx, x);
      stats->reduction_erel_mean = m / samples;
      stats->reduction_erel_max = mx;
      stats->sampled = samples;
    }
  }
  return out;
}

// Tilts every lobe of texel t by d (radians, in the tangent plane), keeping each normal's length, to the
// nearest normal the MIP file stores.
void recentre(BrdfLevel& level, std::size_t t, const glm::dvec2& d) {
  if (d == glm::dvec2(0.0)) return;
  for (Lobe& l : level.texel_lobes(t)) {
    const glm::dvec3 nbar(l.normal);
    const double len = glm::length(nbar);
    if (!(len > 0)) continue;
    l.normal = round_normal(glm::vec3(glm::normalize(nbar / len + glm::dvec3(d, 0.0)) * len));
  }
}

// The radial corrections of the levels from kFirstCorrectedLevel on (radial_correction.h), each level's
// lobes re-centred first when asked; returns their grid.
RadialGrid build_corrections(const MaterialTexels& m, std::vector<BrdfLevel>& levels, bool recentre_lobes) {
  const Extent level0{m.width, m.height};
  float roughness_min = 1.0f;
  for (float r : m.roughness) roughness_min = std::min(roughness_min, r);
  const double alpha_min = gltf_alpha(roughness_min);  // α grows with roughness
  const RadialGrid grid = RadialGrid::for_sharpest(alpha_min * alpha_min);
  // The true profiles of the level below, carried up exactly (area-weighted means of the children's).
  std::vector<RadialProfile> below;
  std::vector<AzimuthalHarmonics> below_harmonics;
  for (int level = kFirstCorrectedLevel; level < static_cast<int>(levels.size()); ++level) {
    const Extent e = levels[static_cast<std::size_t>(level)].extent;
    const std::size_t texels = static_cast<std::size_t>(e.width) * e.height;
    std::vector<RadialProfile> truth(texels, RadialProfile{});
    std::vector<AzimuthalHarmonics> harmonics(texels, AzimuthalHarmonics{});
    BrdfLevel& out = levels[static_cast<std::size_t>(level)];
    out.correction.assign(texels, RadialCorrection{});
    tbb::parallel_for(0, e.height, [&](int j) {
      std::array<Lobe, kUnionCap> buf;
      for (int i = 0; i < e.width; ++i) {
        const std::size_t t = static_cast<std::size_t>(j) * e.width + i;
        if (level == kFirstCorrectedLevel) {
          const int cnt = gather_children(level0, level, i, j, levels[static_cast<std::size_t>(level - 1)], m, buf);
          const std::span<const Lobe> children(buf.data(), static_cast<std::size_t>(cnt));
          add_to_profile(grid, children, truth[t], &harmonics[t]);
        } else {
          const Span cx = child_span(level0.width, level, i), cy = child_span(level0.height, level, j);
          const double total = static_cast<double>(level0_span(level0.width, level, i).size()) *
                               level0_span(level0.height, level, j).size();
          const int fine_width = levels[static_cast<std::size_t>(level - 1)].extent.width;
          for (int y = cy.begin; y < cy.end; ++y)
            for (int x = cx.begin; x < cx.end; ++x) {
              const double share = static_cast<double>(level0_span(level0.width, level - 1, x).size()) *
                                   level0_span(level0.height, level - 1, y).size() / total;
              const std::size_t child = static_cast<std::size_t>(y) * fine_width + x;
              const RadialProfile& c = below[child];
              const AzimuthalHarmonics& ch = below_harmonics[child];
              for (std::size_t r = 0; r < RadialGrid::kNodes; ++r) {
                truth[t][r] += share * c[r];
                for (std::size_t k = 0; k < 4; ++k) harmonics[t][r][k] += share * ch[r][k];
              }
            }
        }
        if (recentre_lobes) recentre(out, t, recentring_tilt(grid, harmonics[t], out.texel_lobes(t)));
        out.correction[t] = correction_to(grid, truth[t], harmonics[t], out.texel_lobes(t));
      }
    });
    below = std::move(truth);
    below_harmonics = std::move(harmonics);
  }
  return grid;
}

}  // namespace

BrdfPyramid BrdfPyramid::build(const MaterialTexels& m, const BrdfBuildOptions& options,
                               std::vector<BrdfLevelStats>* stats) {
  BrdfPyramid p;
  p.level0_ = {m.width, m.height};
  p.max_lobes_ = std::clamp(options.reduction.max_lobes, 1, kMaxLobes);
  p.tintable_ = options.tint;
  const int n = level_count(p.level0_);
  if (n == 0) return p;
  if (stats) stats->assign(static_cast<std::size_t>(n), BrdfLevelStats{1.0, 1, 0.0, 0.0, 0});
  p.levels_.push_back(level_zero(p.level0_));
  for (int level = 1; level < n; ++level)
    p.levels_.push_back(level_from_below(p.level0_, level, p.levels_.back(), m, options,
                                         stats ? &(*stats)[static_cast<std::size_t>(level)] : nullptr));
  // Stretched lobes take no radial correction: its premise, that the lobes' error lies in their radial
  // profile about the normal, fails for lobes whose azimuthal shape is their own (radial_correction.h).
  if (options.radial_correction && n > kFirstCorrectedLevel && !m.has_anisotropy()) p.grid_ = build_corrections(m, p.levels_, options.recentre);
  if (m.has_coat()) {
    // The coat lobes, reduced as the base's are (level 0's are the texels').
    p.coat_.push_back(level_zero(p.level0_));
    for (int level = 1; level < n; ++level)
      p.coat_.push_back(level_from_below(p.level0_, level, p.coat_.back(), m, options, nullptr, true));
  }
  if (m.has_sheen()) {
    // The sheen's means, as the parameter pyramid takes them; level 0's are the texels'.
    p.sheen_.push_back(sheen_level0(m));
    for (int level = 1; level < n; ++level) p.sheen_.push_back(sheen_from_below(p.level0_, level, p.sheen_.back()));
    std::vector<SheenLayer>().swap(p.sheen_.front());
  }
  return p;
}

int BrdfPyramid::bytes_per_texel(int level) const {
  const BrdfLevel& l = this->level(level);
  return l.slots * (kBytesPerLobe + (l.specular_layer() ? kBytesPerSpecularLayer : 0) +
                    (l.tint_layer() ? kBytesPerTintLayer : 0) + (l.stretch_layer() ? kBytesPerStretch : 0) +
                    (l.transmission_layer() ? kBytesPerTransmission : 0) +
                    (l.transmission90_layer() ? kBytesPerTransmission90 : 0) +
                    (l.transmission_stretch_layer() ? kBytesPerTransmissionStretch : 0) +
                    (l.diffuse_transmission_layer() ? kBytesPerDiffuseTransmission : 0) +
                    (l.diffuse_transmission90_layer() ? kBytesPerDiffuseTransmission90 : 0)) +
         (l.correction.empty() ? 0 : kBytesPerCorrection) + coat_bytes_per_texel(level) + sheen_bytes_per_texel(level);
}

int BrdfPyramid::sheen_bytes_per_texel(int level) const {
  if (sheen_.empty() || level == 0) return 0;
  return this->level(level).slots * kBytesPerSheenShare;
}

int BrdfPyramid::coat_bytes_per_texel(int level) const {
  if (coat_.empty() || level == 0) return 0;
  return coat_[static_cast<std::size_t>(level)].slots * kBytesPerCoatLobe + this->level(level).slots * kBytesPerCoatShare;
}

BrdfPyramid BrdfPyramid::from_levels(const MaterialTexels& m, int max_lobes, std::vector<BrdfLevel> coarse,
                                     const RadialGrid& grid, bool tintable, std::vector<BrdfLevel> coat,
                                     std::vector<std::vector<SheenLayer>> sheen) {
  BrdfPyramid p;
  p.grid_ = grid;
  p.tintable_ = tintable;
  p.level0_ = {m.width, m.height};
  p.max_lobes_ = max_lobes;
  const int n = level_count(p.level0_);
  if (static_cast<int>(coarse.size()) + 1 != n || !(coat.empty() || coat.size() == coarse.size()))
    throw Error("BRDF pyramid: " + std::to_string(coarse.size() + 1) + " levels (" + std::to_string(coat.size()) +
                " of the coat) for a " + std::to_string(m.width) + "x" + std::to_string(m.height) +
                " level 0 (expected " + std::to_string(n) + ")");
  // Whether a stored level has the shape of level l's: its extent, counts within its slots, lobes packed.
  const auto well_formed = [&](const BrdfLevel& c, std::size_t l) {
    const Extent e = level_extent(p.level0_, static_cast<int>(l));
    const std::size_t texels = static_cast<std::size_t>(e.width) * e.height;
    bool packed = c.extent == e && c.slots >= 1 && c.slots <= kMaxLobes && c.counts.size() == texels &&
                  c.first.size() == texels && c.single.size() == texels;
    for (std::size_t t = 0, next = 0; packed && t < texels; next += c.counts[t] >= 2 ? c.counts[t] : 0, ++t)
      packed = c.counts[t] <= c.slots && c.first[t] <= c.lobes.size() &&
               (c.counts[t] < 2 || (c.first[t] == next && next + c.counts[t] <= c.lobes.size()));
    return packed && (c.correction.empty() || (c.correction.size() == texels && grid.inner > 0));
  };
  if (!sheen.empty()) {
    if (sheen.size() != coarse.size() + 1) throw Error("BRDF pyramid: the sheen has the wrong number of levels");
    for (std::size_t l = 1; l < sheen.size(); ++l) {
      const Extent e = level_extent(p.level0_, static_cast<int>(l));
      if (sheen[l].size() != static_cast<std::size_t>(e.width) * e.height)
        throw Error("BRDF pyramid: the sheen's level " + std::to_string(l) + " has the wrong size");
    }
    std::vector<SheenLayer>().swap(sheen.front());
    p.sheen_ = std::move(sheen);
  }
  p.levels_.push_back(level_zero(p.level0_));
  if (!coat.empty()) p.coat_.push_back(level_zero(p.level0_));
  for (std::size_t l = 0; l < coarse.size(); ++l) {
    if (!well_formed(coarse[l], l + 1) || !(coat.empty() || (well_formed(coat[l], l + 1) && coat[l].correction.empty())))
      throw Error("BRDF pyramid: level " + std::to_string(l + 1) + " has the wrong shape");
    p.levels_.push_back(std::move(coarse[l]));
    if (!coat.empty()) p.coat_.push_back(std::move(coat[l]));
  }
  return p;
}

}  // namespace svbrdf
