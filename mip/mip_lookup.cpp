#include "mip/mip_lookup.h"

#include <algorithm>
#include <cmath>

#include "base/series_log.h"
#include "textures/sampler.h"

namespace svbrdf {

namespace {

// floor for |x| < 2^31 without a libm call (the release build targets SSE2, which has no rounding
// instruction; these run several times per lookup).
int floor_int(float x) {
  const int i = static_cast<int>(x);
  return x < static_cast<float>(i) ? i - 1 : i;
}

// 1/k for the probe counts k = 1..kMaxProbes (index 0 unused): multiplications where a lookup would
// otherwise queue more divisions on the divider.
constexpr float kInverse[kMaxProbes + 1] = {0.0f, 1.0f, 1.0f / 2, 1.0f / 3, 1.0f / 4, 1.0f / 5, 1.0f / 6, 1.0f / 7, 1.0f / 8};
static_assert(kMaxProbes == 8, "kInverse lists 1/k up to kMaxProbes");

// The footprint's filter: the continuous level, the number of probes and where they sit.
struct FilterShape {
  glm::vec2 uv{0.0f};
  glm::vec2 major_uv{0.0f};  // the footprint's major axis in uv (the probes span it)
  int probes = 1;
  int level = 0;     // lower level of the trilinear pair
  float t = 0.0f;    // weight of level + 1
  float lambda = 0.0f;
};

[[gnu::always_inline]] inline FilterShape filter_shape(Extent level0, int levels, const Footprint& f, int max_probes) {
  FilterShape s;
  max_probes = std::clamp(max_probes, 1, kMaxProbes);
  s.uv = f.uv;
  if (!std::isfinite(s.uv.x) || !std::isfinite(s.uv.y)) s.uv = glm::vec2(0.0f);
  // The footprint's axes in level-0 texels.
  const glm::vec2 scale(static_cast<float>(level0.width), static_cast<float>(level0.height));
  glm::vec2 ax = f.duv_dx * scale, ay = f.duv_dy * scale;
  glm::vec2 mx = f.duv_dx, my = f.duv_dy;
  if (!std::isfinite(ax.x) || !std::isfinite(ax.y)) ax = glm::vec2(0.0f), mx = glm::vec2(0.0f);
  if (!std::isfinite(ay.x) || !std::isfinite(ay.y)) ay = glm::vec2(0.0f), my = glm::vec2(0.0f);
  float lx = glm::length(ax), ly = glm::length(ay);
  // A footprint so large that its length overflows (a footprint scale of 1e30) reads the coarsest
  // level at its centre: no probe offsets, no NaN from ∞/∞ reaching an int conversion.
  if (!std::isfinite(lx) || !std::isfinite(ly)) {
    s.level = levels - 1;
    s.lambda = static_cast<float>(levels - 1);
    return s;
  }
  // The longer axis is the major one (as selects: which one it is is a coin toss for round footprints).
  const float la = std::max(lx, ly), lb = std::min(lx, ly), y_major = static_cast<float>(ly > lx);
  s.major_uv = mx + y_major * (my - mx);
  const float minor = std::max(lb, la * kInverse[max_probes]);
  s.probes = minor > 0 ? std::clamp(-floor_int(-(la / minor - 1e-3f)), 1, max_probes) : 1;
  // Below one texel (or a denormal) the level is 0; above 2^31 texels, the coarsest.
  s.lambda = minor >= 1.0f ? std::min(series_log2(std::min(minor, 2e9f)), static_cast<float>(levels - 1)) : 0.0f;
  s.level = static_cast<int>(s.lambda);
  s.t = s.lambda - static_cast<float>(s.level);
  if (s.level >= levels - 1) s.level = levels - 1, s.t = 0.0f;
  return s;
}

glm::vec2 probe_uv(const FilterShape& s, int p) {
  if (s.probes == 1) return s.uv;
  return s.uv + ((static_cast<float>(p) + 0.5f) * kInverse[s.probes] - 0.5f) * s.major_uv;
}

// Bilinear weights of one level at uv under the texture's wrap modes, applied to this level's texel
// indices as a GPU samples a MIP level (OpenGL 4.6 §8.14.2): a clamped axis repeats its edge texel of
// the level and never reaches the opposite edge; a mirrored one reads the level mirrored, which for
// power-of-two sizes is the mirror of level 0 averaged (a level-L texel covers 2^L level-0 texels
// and the mirror axis falls on a texel boundary of every level). Columns x0, x1 with fx, rows y0, y1
// with fy.
struct Bilinear {
  int x0, x1, y0, y1;
  float fx, fy;
};
struct Axis {
  int i0, i1;
  float f;
};
[[gnu::always_inline]] inline Axis bilinear_axis(float t, int n, WrapMode mode) {
  // texel_coordinate brings far or non-finite coordinates near the texture (sampler.h), so the floor
  // below fits an int.
  const float x = texel_coordinate(t, n, mode) - 0.5f;
  const int x0 = floor_int(x);
  return {wrap_texel(x0, n, mode), wrap_texel(x0 + 1, n, mode), x - static_cast<float>(x0)};
}
[[gnu::always_inline]] inline Bilinear bilinear(Extent e, glm::vec2 uv, WrapModes wrap) {
  const Axis u = bilinear_axis(uv.x, e.width, wrap.s), v = bilinear_axis(uv.y, e.height, wrap.t);
  return {u.i0, u.i1, v.i0, v.i1, u.f, v.f};
}

void add_bilinear(FilterTaps& out, Extent e, int level, glm::vec2 uv, WrapModes wrap, float weight) {
  if (!(weight > 0)) return;
  const Bilinear b = bilinear(e, uv, wrap);
  const float w[4] = {(1 - b.fx) * (1 - b.fy), b.fx * (1 - b.fy), (1 - b.fx) * b.fy, b.fx * b.fy};
  const int xs[4] = {b.x0, b.x1, b.x0, b.x1}, ys[4] = {b.y0, b.y0, b.y1, b.y1};
  for (int k = 0; k < 4; ++k)
    if (w[k] > 0) out.taps[static_cast<std::size_t>(out.count++)] = {level, xs[k], ys[k], weight * w[k]};
}

// Splits u ∈ [0, 1) at p: which side (0 or 1), and u rescaled to [0, 1) within it. (p ∈ (0, 1] here —
// 1 − t, 1 − fx, 1 − fy — and u < 1, so the side chosen never has zero width.) The side is a 0/1
// factor, not a branch: u is random, so a branch would be mispredicted half the time; and one
// division, not a reciprocal of each side: a lookup's divisions queue on the one divider.
int split(float& u, float p) {
  const int high = static_cast<int>(u >= p);
  const float h = static_cast<float>(high);
  const float width = std::max(p + h * (1.0f - 2.0f * p), 1e-30f);  // p below, 1 − p above
  u = std::min(std::max(u - h * p, 0.0f) / width, 0.99999994f);
  return high;
}

}  // namespace

FilterTaps filter_taps(Extent level0, int levels, const Footprint& f, WrapModes wrap, int max_probes) {
  FilterTaps out;
  const FilterShape s = filter_shape(level0, levels, f, max_probes);
  out.level = s.lambda;
  out.probes = s.probes;
  const float w = kInverse[s.probes];
  for (int p = 0; p < s.probes; ++p) {
    const glm::vec2 at = probe_uv(s, p);
    add_bilinear(out, level_extent(level0, s.level), s.level, at, wrap, w * (1.0f - s.t));
    if (s.t > 0) add_bilinear(out, level_extent(level0, s.level + 1), s.level + 1, at, wrap, w * s.t);
  }
  return out;
}

float filter_level(Extent level0, int levels, const Footprint& f, int max_probes) {
  return filter_shape(level0, levels, f, max_probes).lambda;
}

FilterTap select_tap(Extent level0, int levels, const Footprint& f, float u, WrapModes wrap, int max_probes) {
  const FilterShape s = filter_shape(level0, levels, f, max_probes);
  u = std::clamp(std::isfinite(u) ? u : 0.0f, 0.0f, 0.99999994f);
  // One choice per stage, each with the probability of its weight: probe (uniform), level (1 − t, t),
  // column (1 − fx, fx), row (1 − fy, fy); the product is the tap's weight in filter_taps.
  const int p = std::min(s.probes - 1, static_cast<int>(u * static_cast<float>(s.probes)));
  u = std::min(u * static_cast<float>(s.probes) - static_cast<float>(p), 0.99999994f);
  const int level = s.level + split(u, 1.0f - s.t);
  const Bilinear b = bilinear(level_extent(level0, level), probe_uv(s, p), wrap);
  const int x = b.x0 + split(u, 1.0f - b.fx) * (b.x1 - b.x0);
  const int y = b.y0 + split(u, 1.0f - b.fy) * (b.y1 - b.y0);
  return {level, x, y, 1.0f};
}

FilterTap select_tap(const FilterTaps& taps, float u) {
  float acc = 0;
  for (int k = 0; k < taps.count; ++k) {
    acc += taps.taps[static_cast<std::size_t>(k)].weight;
    if (u < acc) return taps.taps[static_cast<std::size_t>(k)];
  }
  // Rounding left u past the last boundary: the last tap with weight.
  for (int k = taps.count - 1; k >= 0; --k)
    if (taps.taps[static_cast<std::size_t>(k)].weight > 0) return taps.taps[static_cast<std::size_t>(k)];
  return {};
}

LobeMixtureBsdf lookup_brdf(const MipData& mip, const Footprint& footprint, float u, WrapModes wrap, int max_probes) {
  // One named result on every path, so it is built in place (a copy is 0.9 KB).
  LobeMixtureBsdf b;
  if (mip.brdf.levels() == 0) return b;
  const FilterTap t = select_tap(mip.brdf.level0(), mip.brdf.levels(), footprint, u, wrap, max_probes);
  if (t.level >= 1) mip.brdf.prefetch(t.level, t.i, t.j);  // the base's and the coat's reads at once
  Lobe scratch, coat_scratch;
  b.assign(brdf_texel(mip, t.level, t.i, t.j, scratch), brdf_coat(mip, t.level, t.i, t.j, coat_scratch).lobes);
  b.set_correction(mip.brdf.correction(t.level, t.i, t.j), &mip.brdf.radial_grid());
  if (const SheenLayer* sheen = brdf_sheen(mip, t.level, t.i, t.j)) b.set_sheen(*sheen);
  return b;
}

ParamTexel filter_params(const ParamPyramid& pyramid, const Footprint& footprint, WrapModes wrap, int max_probes,
                         SpecularLayer* specular, ParamCoat* coat, SheenLayer* sheen, AnisotropyLayer* anisotropy,
                         float* transmission, DiffuseTransmissionLayer* diffuse_transmission) {
  const ParamStore store{pyramid.level0(),     pyramid.levels(),       pyramid.ior(),
                         !pyramid.specular_level(0).empty(), pyramid.has_coat(), pyramid.has_sheen(),
                         pyramid.has_anisotropy(), pyramid.has_transmission(), pyramid.has_diffuse_transmission()};
  return filter_params_of(
      store,
      [&](int level, int i, int j, ParamSpecular* s, ParamCoat* c, SheenLayer* h,
          AnisotropyLayer* a, float* tr, DiffuseTransmissionLayer* d) -> const ParamTexel& {
        if (s) {
          const SpecularLayer l = pyramid.specular(level, i, j);
          *s = {l.specular, l.color};
        }
        if (c) *c = *pyramid.coat(level, i, j);
        if (h) *h = *pyramid.sheen(level, i, j);
        if (a) *a = *pyramid.anisotropy(level, i, j);
        if (tr) *tr = *pyramid.transmission(level, i, j);
        if (d) *d = *pyramid.diffuse_transmission(level, i, j);
        return pyramid.texel(level, i, j);
      },
      footprint, wrap, max_probes, specular, coat, sheen, anisotropy, transmission, diffuse_transmission);
}

Lobe lookup_param(const ParamPyramid& pyramid, const Footprint& footprint, TextureFilter filter, WrapModes wrap,
                  int max_probes) {
  SpecularLayer layer;
  AnisotropyLayer aniso;
  float transmission = 0.0f;
  DiffuseTransmissionLayer diffuse_transmission;
  const ParamTexel t = filter_params(pyramid, footprint, wrap, max_probes, &layer, nullptr, nullptr, &aniso,
                                     &transmission, &diffuse_transmission);
  return param_lobe(t, filter, layer, aniso, transmission, diffuse_transmission);
}

}  // namespace svbrdf
