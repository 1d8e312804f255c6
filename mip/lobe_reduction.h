#pragma once
// Reducing a union of lobes to a bounded number of lobes: the one approximation of the BRDF pyramid
// (../shared/spec/brdf-mip.md, design notes: "a mixture stays a mixture under averaging").
//
// Merging two lobes keeps everything that averages linearly exact — the diffuse amplitude weight·ρ, the
// weighted means of F0 and of the normals, unnormalized (so the lobes' diffuse response E[ρ·n]·wi is
// kept), and of each lobe's coat share (coat_layer.h) — and matches two moments of the specular shape (lobe.h): the tail coefficient A (far from the
// peak D ≈ A/(π·tan⁴θ·cos⁴θ); A is linear in the lobes, so it adds exactly) and the peak P (π·D at
// the normal; each lobe's peak widened by its tilt to the merged normal, α² + γ·tan²θ, as LEAN mapping
// composes slope variances, Olano & Baker 2010, before they add — blended with the union's exact D at
// the merged normal where the merge becomes a spread core; lobe_reduction.cpp says why). The merged
// lobe is the one shape of lobe.h with that A and P (lobe_fit.h): a log-uniform mixture of GGX
// roughness when A·P ≥ 1 (roughness spread: heavier tails than one GGX), a GGX core with a Beckmann
// share when A·P < 1 (normal spread: lighter tails); a core narrower than ~4° also matches a third
// moment, its mass within 2.8° of its normal, with a Beckmann share wider than the GGX one (its skirt),
// and a mixture whose union is much sharper at its centre than the log-uniform band (sharp lobes with
// rough ones) matches its mass within its core, with a GGX atom at its lower end under the band or
// under a second atom. For two GGX lobes of α² 0.03 and 0.12 this keeps D within 1.5 % from the peak
// to 45° off it, where any single GGX misses by 15-35 %; the metal-tray level means, which the lobes' tails carry under oblique
// light, stay within 2 % to the coarsest level (bench/results/mip.md).
//
// GGX loses energy as α grows (single scattering), so a merged lobe would not reflect the flux of the
// two it replaces; its specular part is rescaled to keep their specular albedo summed over θi = 0°,
// 45°, 75° (a tabulated quadrature), through its weight, with ρ divided by the same factor.
//
// Which lobes to merge: first the whole union into one lobe, kept when its estimated error (below)
// is within `tolerance` of the texel's own norm — most texels of smooth regions end there, after one
// merge instead of the ~n² of the pairwise search. Otherwise greedily the pair whose merge costs least
// under a closed-form estimate of the squared L2 error it adds (merge_cost.h: each specular lobe
// seen as a Gaussian of reflected directions blurred to the metric's ~6° resolution, whose L2 inner
// products are closed form; a term for the horizons; a log-space error of the merged D profile against
// the pair's, which the moments do not pin; a small term for the mixture's highlight about the
// geometric normal), until at most `max_lobes` remain; past that, merges continue while the
// accumulated estimate stays below `tolerance`² of the texel's own squared norm (the lobe count is
// chosen per texel by the estimated reduction error, up to max_lobes), so uniform regions end up with
// one lobe.
//
// Where it is written (the files but this one are private to mip/): lobe_reduction.cpp, the merge and
// the search; merge_cost.h, the cost model; lobe_fit.h, the merged lobe's shape; albedo_table.h, the
// specular flux merges keep; reduction_numerics.h, the numerical tools.
#include <span>

#include "mip/lobe.h"

namespace svbrdf {

inline constexpr int kMaxLobes = 8;
// The default --lobes, chosen by the measurements in bench/results/mip.md.
inline constexpr int kDefaultLobes = 4;

// The weight of the cost's highlight term at h = z (merge_cost.h, union_cost): the blurred L2 cannot
// see a narrow lobe moved by a degree or two, the metric's mirror pairs can. Lower lets glossy lobes
// with tilted normals merge; higher keeps polished sub-lobes apart and merges rough lobes into them.
// Chosen by sweeps (docs/mip-algorithm.md, §9).
inline constexpr double kPeakWeight = 2e-4;
// The share of the LEAN estimate in the peak of a merged lobe that becomes a spread core, the rest the
// union's exact D at the merged normal (lobe_reduction.cpp, merge_union, says why). Chosen by the
// same sweeps.
inline constexpr double kLeanPeakShareSpread = 0.4;

struct ReductionOptions {
  int max_lobes = kDefaultLobes;
  float tolerance = 0.01f;    // relative L2 error estimate allowed for merges below max_lobes
  float spread_scale = 1.0f;  // γ in α² += γ·E[tan²θ]
  double peak_weight = kPeakWeight;
  double lean_peak_share_spread = kLeanPeakShareSpread;
};

// Gives a lobe the transmission shape of moments A and P (lobe.h "Transmission"): GGX of α² = 1/P
// where A·P ≤ 1 + 1e-6, else the band with l·h = A/P and sinh(s)/s = √(A·P), s = ln(h/l)/2 (its
// L(l, h) = √(l·h)·sinh(s)/s = A and L/(l·h) = P). Newton from s₀ = √(6(√(A·P) − 1)), which is past the
// root (sinh(s)/s ≥ 1 + s²/6) of a convex increasing function, so it descends to it monotonically.
void set_transmission_shape(Lobe& l, double tail, double peak);

Lobe merge_lobes(const Lobe& a, const Lobe& b, float spread_scale = 1.0f);

// Reduces lobes[0, n) in place to at most options.max_lobes lobes (n ≤ 9·kMaxLobes), sorted by weight,
// largest first, and returns their count. Allocation-free.
int reduce_lobes(std::span<Lobe> lobes, int n, const ReductionOptions& options);

}  // namespace svbrdf
