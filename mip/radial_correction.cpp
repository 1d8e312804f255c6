#include "mip/radial_correction.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/packing.hpp>

#include "base/math.h"
#include "base/series_log.h"
#include "mip/azimuthal_mean.h"

namespace svbrdf {

namespace {
// θ of node 1 against the sharpest lobe's α: inside its core, where a sharp lobe's profile turns.
constexpr double kInnerPerAlpha = 1.0;
constexpr double kInnerMin = radians_of(0.03), kInnerMax = radians_of(1.0);
// The gate's amplitudes: full correction below kGateOn, none from kGateOff.
constexpr double kGateOn = 0.05, kGateOff = 0.15;

bool gated(const RadialGrid& grid, std::size_t r) { return grid.theta[r] > radians_of(RadialGrid::kGateFromDeg); }

float to_half(float x) { return glm::unpackHalf1x16(glm::packHalf1x16(x)); }
}  // namespace

RadialGrid RadialGrid::for_sharpest(double alpha2_min) {
  return with_inner(static_cast<float>(std::clamp(kInnerPerAlpha * std::sqrt(std::max(alpha2_min, 0.0)), kInnerMin, kInnerMax)));
}

RadialGrid RadialGrid::with_inner(float inner, float outer_deg) {
  RadialGrid g;
  g.inner = inner;
  g.outer_deg = outer_deg;
  const double half_inner = std::sin(0.5 * double(inner));
  const double u1 = 2.0 * half_inner * half_inner, un = 1.0 - std::cos(radians_of(double(outer_deg)));  // 1 − cos, precise
  const double step = std::log(un / u1) / (kNodes - 2);
  g.u1 = static_cast<float>(u1);
  g.log_u1 = static_cast<float>(std::log(u1));
  g.inv_step = static_cast<float>(1.0 / step);
  const double u_fade = 1.0 - std::cos(radians_of(kFadePerOuter * outer_deg));
  g.log_u_outer = static_cast<float>(std::log(un));
  g.inv_fade = static_cast<float>(1.0 / std::log(u_fade / un));
  g.theta[0] = 0.0;
  for (int r = 1; r < kNodes; ++r) g.theta[static_cast<std::size_t>(r)] = std::acos(1.0 - u1 * std::exp(step * (r - 1)));
  return g;
}

// add_to_profile at nodes [0, nodes), with the harmonics (when given) from node harmonics_from on.
void accumulate_profile(const RadialGrid& grid, std::span<const Lobe> lobes, RadialProfile& profile, AzimuthalHarmonics* harmonics,
                        std::size_t harmonics_from, std::size_t nodes) {
  for (const Lobe& l : lobes) {
    if (!(l.weight > 0)) continue;
    const LobeShape<double> s = lobe_shape<double>(l, false);
    // Weighted by the lobe's specular reflectance: R corrects the light the lobes reflect, and lobes of
    // different F0 (a metal's clean and its oily texels) carry different shares of it at each angle.
    const double w = double(l.weight) * (double(l.f0.x) + l.f0.y + l.f0.z) / 3.0;
    // A lobe's D is even about its own azimuth φ₀, so ⟨D cos n(φ − φ₀)⟩ = Cₙ is all it has:
    // ⟨D cos nφ⟩ = Cₙ cos nφ₀ and ⟨D sin nφ⟩ = Cₙ sin nφ₀.
    const double rxy = std::hypot(s.n.x, s.n.y);
    const double c1 = rxy > 0 ? s.n.x / rxy : 1.0, s1 = rxy > 0 ? s.n.y / rxy : 0.0;
    const double c2 = c1 * c1 - s1 * s1, s2 = 2 * c1 * s1;
    for (std::size_t r = 0; r < nodes; ++r) {
      if (!harmonics || r < harmonics_from) {
        profile[r] += w * azimuthal_mean_d(s, grid.theta[r]);
        continue;
      }
      const std::array<double, 3> f = azimuthal_fourier_d(s, grid.theta[r]);
      profile[r] += w * f[0];
      (*harmonics)[r][0] += w * f[1] * c1;
      (*harmonics)[r][1] += w * f[1] * s1;
      (*harmonics)[r][2] += w * f[2] * c2;
      (*harmonics)[r][3] += w * f[2] * s2;
    }
  }
}

void add_to_profile(const RadialGrid& grid, std::span<const Lobe> lobes, RadialProfile& profile, AzimuthalHarmonics* harmonics) {
  accumulate_profile(grid, lobes, profile, harmonics, 1, RadialGrid::kNodes);
}

// The first node beyond kGateFromDeg, and so the end of the core.
std::size_t first_gated(const RadialGrid& grid) {
  std::size_t r = 0;
  while (r < RadialGrid::kNodes && !gated(grid, r)) ++r;
  return r;
}

double correction_gate(const std::array<double, 4>& t, const std::array<double, 4>& o) {
  const double amplitude = 2 * (std::hypot(t[0] - o[0], t[1] - o[1]) + std::hypot(t[2] - o[2], t[3] - o[3]));
  return std::clamp((kGateOff - amplitude) / (kGateOff - kGateOn), 0.0, 1.0);
}

RadialCorrection correction_to(const RadialGrid& grid, const RadialProfile& truth, const AzimuthalHarmonics& truth_harmonics,
                               std::span<const Lobe> lobes) {
  RadialProfile own{};
  AzimuthalHarmonics own_harmonics{};
  accumulate_profile(grid, lobes, own, &own_harmonics, first_gated(grid), RadialGrid::kNodes);  // the gate's harmonics only
  RadialCorrection c;
  // The gate only closes outward: a texel whose lobes miss the truth's azimuthal shape at one node gets
  // no more correction farther out (the tile roof's shapes agree again at 30°, where its ratio of 0.8
  // would darken 22.5° in between, which needs more light in the plane of its slopes, not less).
  double gate = 1.0;
  for (std::size_t r = 0; r < RadialGrid::kNodes; ++r) {
    if (!(own[r] > 0 && truth[r] > 0)) {
      c.ratio[r] = 1.0f;
      continue;
    }
    if (gated(grid, r)) {
      std::array<double, 4> t{}, o{};
      for (std::size_t k = 0; k < 4; ++k) t[k] = truth_harmonics[r][k] / truth[r], o[k] = own_harmonics[r][k] / own[r];
      gate = std::min(gate, correction_gate(t, o));
    }
    c.ratio[r] = to_half(static_cast<float>(1 + (truth[r] / own[r] - 1) * (gated(grid, r) ? gate : 1.0)));
  }
  return c;
}

// The re-centring's bounds (radial_correction.h): a tenth of the sharpest lobe's width (the
// linearization's), and 2.5e-4 rad, where a tilt changes a lobe's clipped cosine factor by δ·tan θi,
// 0.1 % at θi = 75°: past that it trades the exact diffuse moment E[ρ·n] for a shape the tilt does not
// have (gray granite's albedo at 75° moved by up to 0.8 % at level 7 with the first bound alone).
constexpr double kMaxTiltPerInner = 0.1;
constexpr double kMaxTilt = 2.5e-4;

glm::dvec2 recentring_tilt(const RadialGrid& grid, const AzimuthalHarmonics& truth_harmonics, std::span<const Lobe> lobes) {
  // The lobes' profile and harmonics at the core's nodes, and P' there by a forward difference of 1 % in θ.
  const std::size_t core = std::min<std::size_t>(first_gated(grid), RadialGrid::kNodes - 1);
  RadialProfile own{}, above{};
  AzimuthalHarmonics own_harmonics{};
  accumulate_profile(grid, lobes, own, &own_harmonics, 1, core);
  constexpr double kStep = 0.01;
  RadialGrid shifted = grid;
  for (std::size_t r = 0; r < core; ++r) shifted.theta[r] *= 1 + kStep;
  accumulate_profile(shifted, lobes, above, nullptr, 0, core);
  double pp = 0;
  glm::dvec2 pd(0.0);
  for (std::size_t r = 1; r < core; ++r) {
    const double slope = (above[r] - own[r]) / (kStep * grid.theta[r]);  // P'(θ)
    const double area = grid.theta[r] * 0.5 * (grid.theta[r + 1] - grid.theta[r - 1]);
    pp += area * slope * slope;
    pd += area * slope * glm::dvec2(truth_harmonics[r][0] - own_harmonics[r][0], truth_harmonics[r][1] - own_harmonics[r][1]);
  }
  if (!(pp > 0)) return glm::dvec2(0.0);
  glm::dvec2 d = -2.0 * pd / pp;
  const double len = glm::length(d);
  const double cap = std::min(kMaxTilt, kMaxTiltPerInner * grid.inner);
  if (len > cap) d *= cap / len;
  return d;
}

float correction_at(const RadialCorrection& c, const RadialGrid& grid, const glm::vec3& h) {
  // u = 1 − cos θ as sin²θ/(1 + cos θ): precise at the smallest angles in single precision.
  const float u = (h.x * h.x + h.y * h.y) / (1.0f + std::max(h.z, 0.0f));
  if (!(u > grid.u1)) {
    const float x = std::max(0.0f, u) / grid.u1;
    return c.ratio[0] + (c.ratio[1] - c.ratio[0]) * x;
  }
  const float log_u = series_logf(u);  // (std::log is a call: this runs at every eval)
  const float t = (log_u - grid.log_u1) * grid.inv_step;
  if (t >= RadialGrid::kNodes - 2) {
    const float last = c.ratio[RadialGrid::kNodes - 1];
    const float s = std::min(1.0f, std::max(0.0f, (log_u - grid.log_u_outer) * grid.inv_fade));
    return last + (1.0f - last) * s;
  }
  const int r = static_cast<int>(t);
  const float x = t - static_cast<float>(r);
  const std::size_t i = static_cast<std::size_t>(r) + 1;
  return c.ratio[i] + (c.ratio[i + 1] - c.ratio[i]) * x;
}

}  // namespace svbrdf
