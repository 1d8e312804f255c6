#pragma once
// Reducing a union of lobes to a bounded number of lobes: the one approximation of the BRDF pyramid
// (../shared/spec/brdf-mip.md, design notes: "a mixture stays a mixture under averaging").
//
// Merging two lobes keeps everything that averages linearly exact — the diffuse amplitude weight·ρ, the
// weighted means of F0 and of the normals, unnormalized (so the lobes' diffuse response E[ρ·n]·wi is
// kept) — and matches the rest: the merged GGX α² is a mean of the lobes' α² (the amplitude-weighted
// harmonic mean for similar roughness, which keeps the height of the highlight; see merge_pair) plus
// the spread of their normals about the merged normal in slope space, α² += γ·E[tan²θ]. For Beckmann lobes
// α² = 2σ² (σ² the per-axis slope variance) and isotropic slopes have E[tan²θ] = 2σ², so γ = 1 is the
// LEAN-mapping composition (Olano & Baker 2010); GGX follows it to first order, and the bumpy presets'
// figures (painted-wall, sandstone: tests/mip/pyramid_test.cpp) are the check.
//
// GGX loses energy as α grows (single scattering), so a merged lobe would not reflect the flux of the
// two it replaces; its specular part is rescaled to keep their specular albedo summed over θi = 0°,
// 45°, 75° (a tabulated quadrature), through its weight, with ρ divided by the same factor.
//
// Which lobes to merge: greedily the pair whose merge costs least under a closed-form estimate of the
// squared L2 error it adds (lobe_reduction.cpp: each specular lobe seen as a Gaussian of reflected
// directions blurred to the metric's ~6° resolution, whose L2 inner products are closed form; a term
// for the horizons; a term for the mixture's highlight about the geometric normal), until at most
// `max_lobes` remain; past that, merges continue while the accumulated estimate stays below
// `tolerance`² of the texel's own squared norm (the lobe count is chosen per texel by the estimated
// reduction error, up to max_lobes), so uniform regions end up with one lobe.
#include <span>

#include "mip/lobe.h"

namespace svbrdf {

inline constexpr int kMaxLobes = 8;
// The default --lobes, chosen by the measurements in bench/results/mip.md.
inline constexpr int kDefaultLobes = 4;

struct ReductionOptions {
  int max_lobes = kDefaultLobes;
  float tolerance = 0.01f;    // relative L2 error estimate allowed for merges below max_lobes
  float spread_scale = 1.0f;  // γ in α² += γ·E[tan²θ]
};

Lobe merge_lobes(const Lobe& a, const Lobe& b, float spread_scale = 1.0f);

// The estimated squared L2 error of replacing a and b by merge_lobes(a, b).
double merge_cost(const Lobe& a, const Lobe& b, const Lobe& merged);

// Reduces lobes[0, n) in place to at most options.max_lobes lobes (n ≤ 9·kMaxLobes), sorted by weight,
// largest first, and returns their count. Allocation-free.
int reduce_lobes(std::span<Lobe> lobes, int n, const ReductionOptions& options);

}  // namespace svbrdf
