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
#include <vector>

#include "mip/metrics.h"

namespace svbrdf {

struct TransmissionFigures {
  double elog_reflected = 0, elog_transmitted = 0;
  double flux_reflected = 0, flux_transmitted = 0;  // flux_transmitted NaN where nothing transmits
  double exact_transmitted = 0;  // Σ L of the exact transmission over the pairs: 0 where nothing transmits
};

// Every level ≥ 1 of `mip`: element k is level k + 1's. A level whose texels are all measured (4 × 4 or
// fewer) takes its exact values as the coverage-weighted means of the finer level's where that level's
// are all measured too (the exact reference is linear in the covered texels), so the coarsest levels
// cost nothing more.
std::vector<TransmissionFigures> measure_transmission(const MipData& mip);

}  // namespace svbrdf
