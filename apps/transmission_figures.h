#pragma once
// The BRDF pyramid's thin-walled transmission (mip/lobe.h "Transmission", docs/mip-algorithm.md §4.6)
// against the exact reference at one level, beside its reflection measured the same way: what
// TransmissionPyramid asserts and what `svbrdf-bake random-family` reports for the seeds that transmit.
//
// At up to 4 × 4 texels spread over the level (every ⌈extent/4⌉-th row and column), each texel's lobes
// as the renderer's mixture evaluates them (mip/lobe_mixture_bsdf.h: coat and sheen included) against
// ExactReference::eval (the covered texels' mean BTDF / BRDF): for wo above the surface and wi above
// (reflected) or wi mirrored below (transmitted), over the directions θ ∈ {0°, 20°, …, 80°} × φ ∈ {0°,
// 45°, …, 315°} (θ = 0 once) — the metric's (../shared/spec/brdf-mip.md) at every other polar angle, a
// quarter of its pairs, since the exact reference of a coarse texel evaluates every covered texel per
// pair — and the three channels, with L = F·|wi.z|:
//   e_log = √mean (log(1 + L̂) − log(1 + L))²,   flux = Σ L̂ / Σ L − 1.
// That "flux" is a sum over these pairs, not an integral: a thin wall sends every texel's light straight
// through, and the straight-through pair of every wi is among them (wo = −wi mirrored: φ + 180°), so
// on glossy texels it is mostly the transmission's peak. What the level transmits in all is measured
// apart, as the directional transmittance of light from below,
//   T(wi) = ∫ f(wi, wo)·wo.z dωo over wo above,   wi = θ 0°, 45°, 75° below (azimuth 0),
// the level's total (every texel, area-weighted) against the exact's, which is the level-0 texels'
// total (T is linear in the texels, as the exact reference is): transmittance = ΣT̂ / ΣT − 1 per θ. Both
// by the same deterministic quadrature of the mixture as the renderer evaluates it (multiple importance
// sampling about each lobe's transmission peak, transmission_figures.cpp), 16² samples a technique and a
// texel at least and kTransmittanceSamples a technique over a level.
#include <array>
#include <vector>

#include "mip/mip.h"
#include "mip/metrics.h"

namespace svbrdf {

struct TransmissionFigures {
  double elog_reflected = 0, elog_transmitted = 0;
  double flux_reflected = 0, flux_transmitted = 0;  // flux_transmitted NaN where nothing transmits
  double exact_transmitted = 0;  // Σ L of the exact transmission over the pairs: 0 where nothing transmits
  // The level's directional transmittance against the exact's − 1, per θ of kAlbedoThetaDeg (NaN
  // where nothing transmits).
  std::array<double, 3> transmittance{};
};

// The polar angles of the directional albedo (random_family_measure.h) and transmittance figures.
inline constexpr std::array<double, 3> kAlbedoThetaDeg{0.0, 45.0, 75.0};
inline constexpr int kTransmittanceSamples = 1 << 16;

// T(wi) = ∫ f(wi, wo)·wo.z dωo of a mixture for wi below, the channels' mean: multi-sample importance
// sampling with the balance heuristic (Veach 1997, §9.2) over n² stratified samples of each technique,
// the cosine about the geometric normal and, for each transmitting lobe, the reflection about its
// transmission shape's half vectors of wi mirrored through its plane (lobe.h transmission_pair): where
// its BTDF peaks, however glossy or stretched. Deterministic: the jitter comes from `stream`.
double directional_transmittance(const LobeMixtureBsdf& bsdf, const glm::dvec3& wi, int n, std::uint64_t stream);

// Every level ≥ 1 of `mip`: element k is level k + 1's. A level whose texels are all measured (4 × 4 or
// fewer) takes its exact values as the coverage-weighted means of the finer level's where that level's
// are all measured too (the exact reference is linear in the covered texels), so the coarsest levels
// cost nothing more.
std::vector<TransmissionFigures> measure_transmission(const MipData& mip);

}  // namespace svbrdf
