#include "mip/mip_lookup.h"

#include <algorithm>
#include <cmath>

namespace svbrdf {

namespace {

int wrap(int i, int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

// Bilinear taps of one level at uv (wrap: repeat).
void add_bilinear(FilterTaps& out, Extent e, int level, glm::vec2 uv, float weight) {
  if (!(weight > 0)) return;
  const float x = uv.x * static_cast<float>(e.width) - 0.5f, y = uv.y * static_cast<float>(e.height) - 0.5f;
  const float fx0 = std::floor(x), fy0 = std::floor(y);
  const float fx = x - fx0, fy = y - fy0;
  // Reduce the integer part modulo the size first so huge coordinates stay exact.
  const int x0 = wrap(static_cast<int>(std::fmod(fx0, static_cast<float>(e.width))), e.width);
  const int y0 = wrap(static_cast<int>(std::fmod(fy0, static_cast<float>(e.height))), e.height);
  const int x1 = wrap(x0 + 1, e.width), y1 = wrap(y0 + 1, e.height);
  const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  const int xs[4] = {x0, x1, x0, x1}, ys[4] = {y0, y0, y1, y1};
  for (int k = 0; k < 4; ++k)
    if (w[k] > 0) out.taps[static_cast<std::size_t>(out.count++)] = {level, xs[k], ys[k], weight * w[k]};
}

}  // namespace

FilterTaps filter_taps(Extent level0, int levels, const Footprint& f, int max_probes) {
  FilterTaps out;
  max_probes = std::clamp(max_probes, 1, kMaxProbes);
  glm::vec2 uv = f.uv;
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) uv = glm::vec2(0.0f);
  // The footprint's axes in level-0 texels.
  const glm::vec2 scale(static_cast<float>(level0.width), static_cast<float>(level0.height));
  glm::vec2 ax = f.duv_dx * scale, ay = f.duv_dy * scale;
  if (!std::isfinite(ax.x) || !std::isfinite(ax.y)) ax = glm::vec2(0.0f);
  if (!std::isfinite(ay.x) || !std::isfinite(ay.y)) ay = glm::vec2(0.0f);
  float la = glm::length(ax), lb = glm::length(ay);
  glm::vec2 major_uv = f.duv_dx;
  if (lb > la) std::swap(la, lb), major_uv = f.duv_dy;
  if (!(la > 0)) major_uv = glm::vec2(0.0f);
  float minor = std::max(lb, la / static_cast<float>(max_probes));
  const int probes = minor > 0 ? std::clamp(static_cast<int>(std::ceil(la / minor - 1e-3f)), 1, max_probes) : 1;
  const float lambda = minor > 0 ? std::clamp(std::log2(minor), 0.0f, static_cast<float>(levels - 1)) : 0.0f;
  out.level = lambda;
  out.probes = probes;
  int l0 = static_cast<int>(std::floor(lambda));
  float t = lambda - static_cast<float>(l0);
  if (l0 >= levels - 1) l0 = levels - 1, t = 0.0f;
  for (int p = 0; p < probes; ++p) {
    const float s = (static_cast<float>(p) + 0.5f) / static_cast<float>(probes) - 0.5f;
    const glm::vec2 at = probes > 1 ? uv + s * major_uv : uv;
    const float w = 1.0f / static_cast<float>(probes);
    add_bilinear(out, level_extent(level0, l0), l0, at, w * (1.0f - t));
    if (t > 0) add_bilinear(out, level_extent(level0, l0 + 1), l0 + 1, at, w * t);
  }
  return out;
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

LobeMixtureBsdf lookup_brdf(const BrdfPyramid& pyramid, const Footprint& footprint, float u, int max_probes) {
  if (pyramid.levels() == 0) return {};
  const FilterTaps taps = filter_taps(pyramid.level0(), pyramid.levels(), footprint, max_probes);
  const FilterTap t = select_tap(taps, u);
  return LobeMixtureBsdf(pyramid.texel(t.level, t.i, t.j));
}

ParamTexel filter_params(const ParamPyramid& pyramid, const Footprint& footprint, int max_probes) {
  ParamTexel sum;
  sum.normal = glm::vec3(0.0f);
  if (pyramid.levels() == 0) return sum;
  const FilterTaps taps = filter_taps(pyramid.level0(), pyramid.levels(), footprint, max_probes);
  for (int k = 0; k < taps.count; ++k) {
    const FilterTap& t = taps.taps[static_cast<std::size_t>(k)];
    const ParamTexel& p = pyramid.texel(t.level, t.i, t.j);
    sum.base_color += t.weight * p.base_color;
    sum.metallic += t.weight * p.metallic;
    sum.roughness += t.weight * p.roughness;
    sum.normal += t.weight * p.normal;
  }
  return sum;
}

Lobe lookup_param(const ParamPyramid& pyramid, const Footprint& footprint, ParamBaseline baseline, int max_probes) {
  return param_lobe(filter_params(pyramid, footprint, max_probes), baseline);
}

}  // namespace svbrdf
