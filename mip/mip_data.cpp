#include "mip/mip_data.h"

#include <chrono>
#include <string>
#include <vector>

#include "base/error.h"
#include "mip/direction_grid.h"
#include "mip/exact_reference.h"

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

std::string_view mode_name(MipMode m) {
  switch (m) {
    case MipMode::exact: return "exact";
    case MipMode::param: return "param";
    case MipMode::toksvig: return "toksvig";
    case MipMode::vmf: return "vmf";
    case MipMode::brdf: return "brdf";
  }
  return "?";
}

std::optional<MipMode> parse_mode(std::string_view name) {
  for (MipMode m : {MipMode::exact, MipMode::param, MipMode::toksvig, MipMode::vmf, MipMode::brdf})
    if (name == mode_name(m)) return m;
  return std::nullopt;
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
ParamBaseline baseline_of(MipMode m) {
  return m == MipMode::toksvig ? ParamBaseline::toksvig : m == MipMode::vmf ? ParamBaseline::vmf : ParamBaseline::param;
}
}  // namespace

void accumulate_brdf_texel(const MipData& mip, int level, int i, int j, double weight, std::span<glm::dvec3> acc) {
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
  Lobe scratch;
  for (const Lobe& l : brdf_texel(mip, level, i, j, scratch)) accumulate_lobe_float(l, weight, acc, scales);
}

glm::dvec3 mode_eval(const MipData& mip, MipMode mode, int level, int i, int j, const glm::dvec3& wi,
                     const glm::dvec3& wo) {
  if (mode == MipMode::exact) return ExactReference(mip.level0).eval(level, i, j, wi, wo);
  const PairTerms<float> p = pair_terms<float>(glm::vec3(wi), glm::vec3(wo));
  if (mode == MipMode::brdf) {
    glm::dvec3 sum(0);
    Lobe scratch;
    const RadialCorrection* c = mip.brdf.correction(level, i, j);
    const float k = c ? correction_at(*c, mip.brdf.radial_grid(), p.h) : 1.0f;
    for (const Lobe& l : brdf_texel(mip, level, i, j, scratch)) sum += glm::dvec3(lobe_eval<float>(l, lobe_shape<float>(l), p, k));
    return sum;
  }
  return glm::dvec3(lobe_eval<float>(param_lobe(mip.param.texel(level, i, j), baseline_of(mode)), p));
}

BrdfTable mode_table(const MipData& mip, MipMode mode, int level, int i, int j) {
  if (mode == MipMode::exact) return ExactReference(mip.level0).table(level, i, j);
  BrdfTable t = make_table();
  if (mode == MipMode::brdf) {
    accumulate_brdf_texel(mip, level, i, j, 1.0, t);
  } else {
    accumulate_lobe_float(param_lobe(mip.param.texel(level, i, j), baseline_of(mode)), 1.0, t);
  }
  return t;
}

int mode_bytes_per_texel(const MipData& mip, MipMode mode, int level) {
  switch (mode) {
    case MipMode::brdf: return level == 0 ? ParamPyramid::kBytesPerTexel : mip.brdf.bytes_per_texel(level);
    case MipMode::exact: {
      const Extent e0 = mip.extent(0), e = mip.extent(level);
      return static_cast<int>(static_cast<long long>(ParamPyramid::kBytesPerTexel) * e0.width * e0.height /
                              (static_cast<long long>(e.width) * e.height));
    }
    default: return ParamPyramid::kBytesPerTexel;
  }
}

}  // namespace svbrdf
