#include "mip/mip_data.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <string>
#include <vector>

#include "base/error.h"
#include "mip/direction_grid.h"
#include "mip/lobe_mixture_bsdf.h"

namespace svbrdf {

MipData build_mip(MaterialTexels level0, const BrdfBuildOptions& options, std::vector<BrdfLevelStats>* stats,
                  double* brdf_seconds) {
  MipData d;
  d.level0 = std::move(level0);
  d.param = ParamPyramid::build(d.level0);
  const auto start = std::chrono::steady_clock::now();
  d.brdf = BrdfPyramid::build(d.level0, options, stats);
  if (brdf_seconds) *brdf_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return d;
}

void check_texel(const MipData& mip, int level, int i, int j) {
  if (level < 0 || level >= mip.levels())
    throw input_error("--level", "level " + std::to_string(level) + " is out of range (the file has levels 0.." +
                                     std::to_string(mip.levels() - 1) + ")");
  const Extent e = mip.extent(level);
  if (i < 0 || i >= e.width || j < 0 || j >= e.height)
    throw input_error("--texel", "texel (" + std::to_string(i) + ", " + std::to_string(j) + ") is out of range (level " +
                                     std::to_string(level) + " is " + std::to_string(e.width) + "x" +
                                     std::to_string(e.height) + ")");
}

namespace {

// acc += weight · f_eff of a texel of base lobes (each tinted by `tint` unless it is 1, their specular
// terms scaled per pair by `scales` where not null) under its coat, over the direction grid's pairs, in
// float as the renderer evaluates it.
void accumulate_texel(std::span<const Lobe> lobes, const CoatTexel& coat, const float* scales, double weight,
                      std::span<glm::dvec3> acc, const glm::vec3& tint) {
  if (!coat.present()) {
    for (const Lobe& l : lobes) accumulate_lobe_float(tint == glm::vec3(1.0f) ? l : tinted(l, tint), weight, acc, scales);
    return;
  }
  // A coated texel's base goes through tables of its own (plain and weighted by each lobe's coat),
  // attenuated per wo with the coat added (coat_layer.h).
  static thread_local BrdfTable base, base_coated;
  base.assign(DirectionGrid::kPairs, glm::dvec3(0));
  base_coated.assign(DirectionGrid::kPairs, glm::dvec3(0));
  for (const Lobe& l : lobes) {
    const Lobe t = tint == glm::vec3(1.0f) ? l : tinted(l, tint);
    accumulate_lobe_float(t, 1.0, base, scales);
    if (l.coat > 0) accumulate_lobe_float(t, l.coat, base_coated, scales);
  }
  accumulate_coat<float>(lobes, coat, base, base_coated, weight, acc);
}

// acc += weight · a texel with a sheen over the direction grid's pairs: the renderer's mixture itself
// (lobe_mixture_bsdf.h), whose eval is the one that carries the sheen (sheen_layer.h).
void accumulate_mixture(const LobeMixtureBsdf& b, double weight, std::span<glm::dvec3> acc) {
  const DirectionGrid& g = DirectionGrid::get();
  for (int p = 0; p < DirectionGrid::kPairs; ++p) {
    const PairTerms<float>& t = g.pair_f(p);
    acc[static_cast<std::size_t>(p)] += weight * glm::dvec3(b.eval(t.wi, t.wo));
  }
}

// The parameter filters' texel (param_pyramid.h param_lobes), the mean coat's lobe made into `out`.
ParamLobes param_texel_lobes(const MipData& mip, TextureFilter filter, int level, int i, int j) {
  const float* transmission = mip.param.transmission(level, i, j);
  return param_lobes(mip.param.texel(level, i, j), filter, mip.param.specular(level, i, j), mip.param.coat(level, i, j),
                     mip.param.sheen(level, i, j), mip.param.anisotropy(level, i, j),
                     transmission ? *transmission : 0.0f, mip.param.diffuse_transmission(level, i, j));
}
CoatTexel coat_of(const ParamLobes& l) {
  if (!l.coated || !(l.coat.weight > 0)) return {};
  return {{&l.coat, 1}};
}

}  // namespace

void accumulate_brdf_texel(const MipData& mip, int level, int i, int j, double weight, std::span<glm::dvec3> acc,
                           const glm::vec3& tint) {
  const RadialCorrection* c = mip.brdf.correction(level, i, j);
  const float* scales = nullptr;
  static thread_local std::vector<float> per_pair;
  if (c) {
    const DirectionGrid& g = DirectionGrid::get();
    per_pair.resize(DirectionGrid::kPairs);
    for (int p = 0; p < DirectionGrid::kPairs; ++p)
      per_pair[static_cast<std::size_t>(p)] = correction_at(*c, mip.brdf.radial_grid(), g.pair_f(p).h);
    scales = per_pair.data();
  }
  Lobe scratch, coat_scratch;
  const CoatTexel coat = brdf_coat(mip, level, i, j, coat_scratch);
  if (const SheenLayer* sheen = brdf_sheen(mip, level, i, j)) {
    std::span<const Lobe> lobes = brdf_texel(mip, level, i, j, scratch);
    std::array<Lobe, kMaxLobes> t;
    if (tint != glm::vec3(1.0f)) {
      const std::size_t n = std::min<std::size_t>(lobes.size(), kMaxLobes);
      for (std::size_t k = 0; k < n; ++k) t[k] = tinted(lobes[k], tint);
      lobes = {t.data(), n};
    }
    LobeMixtureBsdf b(lobes, coat.lobes);
    b.set_correction(c, &mip.brdf.radial_grid());
    b.set_sheen(*sheen);
    accumulate_mixture(b, weight, acc);
    return;
  }
  accumulate_texel(brdf_texel(mip, level, i, j, scratch), coat, scales, weight, acc, tint);
}

void accumulate_param_texel(const MipData& mip, TextureFilter filter, int level, int i, int j, double weight,
                            std::span<glm::dvec3> acc) {
  const ParamLobes l = param_texel_lobes(mip, filter, level, i, j);
  if (mip.param.has_sheen()) {
    LobeMixtureBsdf b({&l.base, 1}, coat_of(l).lobes);
    b.set_sheen(l.sheen);
    accumulate_mixture(b, weight, acc);
    return;
  }
  accumulate_texel({&l.base, 1}, coat_of(l), nullptr, weight, acc, glm::vec3(1.0f));
}

glm::dvec3 texel_eval(const MipData& mip, TextureFilter filter, int level, int i, int j, const glm::dvec3& wi,
                      const glm::dvec3& wo) {
  const PairTerms<float> p = pair_terms<float>(glm::vec3(wi), glm::vec3(wo));
  // The texel's base lobes (with the pyramid's radial correction) and its coat.
  Lobe scratch, coat_scratch;
  std::span<const Lobe> lobes;
  CoatTexel coat;
  float k = 1.0f;
  ParamLobes param;
  const SheenLayer* sheen = nullptr;
  const RadialCorrection* c = nullptr;
  if (filter == TextureFilter::brdf) {
    c = mip.brdf.correction(level, i, j);
    k = c ? correction_at(*c, mip.brdf.radial_grid(), p.h) : 1.0f;
    lobes = brdf_texel(mip, level, i, j, scratch);
    coat = brdf_coat(mip, level, i, j, coat_scratch);
    sheen = brdf_sheen(mip, level, i, j);
  } else {
    param = param_texel_lobes(mip, filter, level, i, j);
    lobes = {&param.base, 1};
    coat = coat_of(param);
    if (mip.param.has_sheen()) sheen = &param.sheen;
  }
  if (sheen) {
    // A texel with a sheen: the renderer's mixture (see accumulate_mixture).
    LobeMixtureBsdf b(lobes, coat.lobes);
    b.set_correction(c, &mip.brdf.radial_grid());
    b.set_sheen(*sheen);
    return glm::dvec3(b.eval(glm::vec3(wi), glm::vec3(wo)));
  }
  glm::vec3 base(0.0f), base_coated(0.0f);
  for (const Lobe& l : lobes) {
    const glm::vec3 f = lobe_eval<float>(l, lobe_shape<float>(l), p, k);
    base += f;
    base_coated += l.coat * f;
  }
  return glm::dvec3(coated_eval(base, base_coated, lobes, coat, p));
}

BrdfTable texel_table(const MipData& mip, TextureFilter filter, int level, int i, int j) {
  BrdfTable t = make_table();
  if (filter == TextureFilter::brdf)
    accumulate_brdf_texel(mip, level, i, j, 1.0, t);
  else
    accumulate_param_texel(mip, filter, level, i, j, 1.0, t);
  return t;
}

int bytes_per_texel(const MipData& mip, TextureFilter filter, int level) {
  if (filter == TextureFilter::brdf && level > 0) return mip.brdf.bytes_per_texel(level);
  return ParamPyramid::kBytesPerTexel + (mip.param.specular_level(0).empty() ? 0 : ParamPyramid::kBytesPerSpecularTexel) +
         (mip.param.has_coat() ? ParamPyramid::kBytesPerCoatTexel : 0) +
         (mip.param.has_sheen() ? ParamPyramid::kBytesPerSheenTexel : 0) +
         (mip.param.has_anisotropy() ? ParamPyramid::kBytesPerAnisotropyTexel : 0) +
         (mip.param.has_transmission() ? ParamPyramid::kBytesPerTransmissionTexel : 0) +
         (mip.param.has_diffuse_transmission() ? ParamPyramid::kBytesPerDiffuseTransmissionTexel : 0);
}

}  // namespace svbrdf
