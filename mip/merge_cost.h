#pragma once
// Private to mip/: included by mip's .cpp files only (lobe_reduction.h is the reduction's public face).
// The reduction's cost model: what it knows of each lobe (Summary), and the estimated squared L2 error
// of replacing a union of lobes by one merged lobe (union_cost; docs/mip-algorithm.md, §4.2) — each
// specular lobe seen as a Gaussian of reflected directions blurred to the metric's resolution, a term
// for the horizons, one for the highlight about the geometric normal, one for the core widths and a
// log-space error of the D profile — and a cheap distance for rough lobes (rough_distance).
#include <array>
#include <cmath>
#include <cstddef>
#include <span>

#include <glm/glm.hpp>

#include "base/math.h"
#include "base/series_log.h"
#include "mip/lobe.h"
#include "mip/slope_stretch.h"

namespace svbrdf::reduction {

// The resolution below which the cost model stops telling specular lobes apart: every lobe is seen
// blurred by a GGX-like kernel of α² = kResolutionAlpha2 (α = 0.1, about 6°, the scale of the metric's
// direction grid). Without it the L2 norm of a lobe grows as 1/α², so the shape differences of
// mirror-like lobes (α ≈ 0.005 against 0.01) would outweigh everything else and a polished tray's
// soft fingerprint glow would be merged away to keep them apart.
constexpr double kResolutionAlpha2 = 0.01;
// The weight of the highlight term for the first try of a texel's whole union as one lobe
// (reduce_lobes; the pairwise merges take ReductionOptions::peak_weight): that try asks
// whether the texel is smooth within the L2 budget, a norm with no peak term; it keeps the small weight.
constexpr double kWholePeakWeight = 1e-5;
// The weight of the log-profile term of union_cost (the shape between peak and tail), and its steps.
constexpr double kProfileWeight = 25.0;
constexpr std::size_t kProfileSteps = 15;
// The profile's step j: tan²θ = 10^(−6 + 7j/(kProfileSteps − 1)), two steps a decade from 10⁻⁶ to 10.
inline double profile_step(std::size_t j) { return std::pow(10.0, -6.0 + 7.0 * double(j) / (kProfileSteps - 1)); }
// The first step at the resolution, tan²θ = 10⁻² = kResolutionAlpha2: the transmission's log profile
// starts there (trans_cost in merge_cost.cpp); the steps below it are the 8 under the resolution.
constexpr std::size_t kResolvedProfileStep = 8;

// A lobe's specular amplitude, its share of the reflected flux for the cost model: F0 plus a little
// for Fresnel's rise toward grazing angles (toward F90), times its weight and cosine factor (the mean
// normal's length).
inline double specular_amp(double weight, double len, double f0, double f90) {
  return weight * len * (f0 + 0.05 * (f90 - f0));
}

// What D of a lobe shape depends on (lobe_d), without the horizons' fields.
struct DShape {
  double alpha2 = 1, alpha2_hi = 0, lmean = 0, ggx = 1, skirt = 1;
  bool two_point = false;
  static DShape of(const LobeShape<double>& sh) {
    return {sh.alpha2, sh.alpha2_hi, sh.lmean, sh.ggx, sh.skirt, sh.two_point};
  }
};

// What the cost model needs of a lobe, computed once per lobe.
struct Summary {
  glm::dvec3 n{0, 0, 1};  // unit normal
  double weight = 0;
  double amp = 0;     // specular amplitude: its share of the reflected flux
  double d_z = 0;     // D at h = z (the geometric normal)
  double rho = 0;     // mean diffuse albedo
  double f0 = 0;      // mean F0
  double f90 = 1;     // F90 (lobe.h)
  double alpha2 = 1;  // the core's width 1/P, for the Gaussian model of union_cost
  double ggx = 1;     // μ, the GGX share of a spread core (lobe.h)
  double tail = 0;    // A: the tail coefficient, D ≈ A/(π t²) far out
  double peak = 1;    // P: π·D at the lobe's own normal
  DShape d_shape;     // its D's shape, for D away from its normal (merge_union)
  double flux = -1;   // its specular flux as keep_specular_flux measures it (< 0: not yet known)
  std::array<double, kProfileSteps> profile{};  // D about its own normal at tan²θ = 10^-6 … 10 (profile_of)
  // Its normal's slope, and its stretch (slope_stretch.h): whether it has one, S, ln S as a vector.
  bool stretched = false;
  Sym2 stretch;
  glm::dvec2 stretch_log{0.0};
  glm::dvec2 slope{0.0};
  // Its transmission (lobe.h "Transmission"): the transmitted amplitude per channel, weight·|normal|
  // times τ plus a little toward τ90 (as amp's F0 toward F90), and the transmission's α²; 0 and 0 for a
  // lobe that transmits nothing.
  glm::dvec3 trans{0.0};
  double alpha2_t = 0;  // the core's width 1/P of its transmission shape (lobe.h transmission_moments)
  double tail_t = 0;    // A of its transmission shape
  std::array<double, kProfileSteps> trans_profile{};  // its transmission's D about its normal (profile_of)
};

// D of a lobe shape at tan²θ = t from its normal: lobe_d's shapes written in t (cos²θ = 1/(1 + t)), so
// no vectors: GGX α²/(π·cos⁴θ·(α² + t)²), the mixture's μ·L(l, h)/(π·cos⁴θ·(l + t)(h + t)), Beckmann
// e^(−t/α²)/(π·α²·cos⁴θ), the exponential by series_exp (4e-7: the reduction compares shapes with
// these, for every candidate merge). 0 past 90° (t infinite).
inline double d_at_tan2(const DShape& sh, double t) {
  if (!std::isfinite(t)) return 0.0;
  const double a2 = sh.alpha2, q = (1 + t) * (1 + t) / kPiD;
  if (sh.alpha2_hi > 0) {
    const double hi = sh.alpha2_hi;
    const double upper = sh.two_point ? hi / ((t + hi) * (t + hi)) : sh.lmean / ((t + a2) * (t + hi));
    return q * (sh.ggx * upper + (1.0 - sh.ggx) * a2 / ((t + a2) * (t + a2)));
  }
  double d = sh.ggx * a2 / ((t + a2) * (t + a2));
  if (sh.ggx != 1.0) {
    const double b2 = a2 * sh.skirt, x = t / b2;
    if (x < 60.0) d += (1.0 - sh.ggx) * double(series_exp(static_cast<float>(-x))) / b2;
  }
  return q * d;
}

// D of a lobe shape about its own normal at kProfileSteps values of tan²θ, log-spaced from 1e-6 to 10:
// d_at_tan2 at each, its branches taken once for the row (this runs for every lobe summarized, and the
// loops over the steps then vectorize); the same arithmetic, so the same numbers. A loop of inlined
// d_at_tan2 calls made reduce_lobes 9 % slower per level-1 texel, hence the copy: change both together.
void profile_of(const DShape& sh, std::array<double, kProfileSteps>& out);

// tan²θ between two unit vectors (∞ at or past 90°).
inline double tan2_between(const glm::dvec3& a, const glm::dvec3& b) {
  const double c = glm::dot(a, b);
  if (c <= 1e-6) return INFINITY;
  return std::max(0.0, 1.0 / (c * c) - 1.0);
}

// The summary of a lobe (its shape from lobe_shape).
Summary summarize(const Lobe& l);

// The L2 inner product, over (wi, wo) pairs, of two specular lobes of amplitude 1: each lobe's
// reflected radiance around its mirror direction approximated by a Gaussian of per-axis variance
// 2α² (the half vector's α²/2, doubled twice by the mirror map), their centres 2·tanθ apart.
// ∫ N(x; μa, Σa) N(x; μb, Σb) dx = N(μa − μb; 0, Σa + Σb) gives exp(−d²/(αa² + αb²)) / (4π(αa² + αb²)),
// times the 2π of wi; both lobes blurred to the resolution kResolutionAlpha2.
inline double spec_inner(double alpha2_a, double alpha2_b, double tan2) {
  if (!std::isfinite(tan2)) return 0.0;
  const double s = alpha2_a + alpha2_b + 2.0 * kResolutionAlpha2, x = tan2 / s;
  // Nearly parallel normals (most pairs of a smooth surface): e^−x by its series (within 3e-9).
  const double g = x < 0.05 ? 1 - x * (1 - x * (0.5 - x * (1.0 / 6 - x * (1.0 / 24)))) : std::exp(-x);
  return g / (2.0 * s);
}

// spec_inner of two lobes: the form above unless one is stretched; then the same Gaussians with the
// lobes' slope matrices, per-axis variances α²·S/2 (slope_stretch.h) and the blur's, whose centres lie
// d = Δ(normal slope) apart: N(d; 0, M), M = (αa²·Sa + αb²·Sb + 2·α²_res·I)/2, is exp(−dᵀM⁻¹d/2)/(2π√det M)
// and the isotropic form's normalization makes it exp(−dᵀM⁻¹d/2)/(4√det M) (M = (s/2)·I gives it back).
// tan2: tan²θ between their normals, as the form above takes it.
inline double spec_inner(const Summary& a, const Summary& b, double tan2) {
  if (!a.stretched && !b.stretched) return spec_inner(a.alpha2, b.alpha2, tan2);
  if (!std::isfinite(tan2)) return 0.0;
  const Sym2 m{0.5 * (a.alpha2 * a.stretch.xx + b.alpha2 * b.stretch.xx) + kResolutionAlpha2,
               0.5 * (a.alpha2 * a.stretch.xy + b.alpha2 * b.stretch.xy),
               0.5 * (a.alpha2 * a.stretch.yy + b.alpha2 * b.stretch.yy) + kResolutionAlpha2};
  const double det = m.det();
  const glm::dvec2 d = a.slope - b.slope;
  const Sym2 inv{m.yy / det, -m.xy / det, m.xx / det};
  return std::exp(-0.5 * inv.quad(d)) / (4.0 * std::sqrt(det));
}

// The lobes of a union being merged: each lobe with its summary.
struct Member {
  const Lobe* lobe;
  const Summary* sum;
};

// Σ_ij amp_i·amp_j·⟨G_i, G_j⟩: the squared L2 norm of the union's specular lobes (spec_inner).
double union_spec_norm2(std::span<const Member> u);

// The transmission's terms of union_cost (trans_cost in merge_cost.cpp) are the reflection's, taken per
// colour channel and averaged over the channels (the transmitted colour is all in the lobes, which no
// diffuse part carries, so lobes whose τ differ in colour as well as in width cannot share one shape):
// the L2 error of the Gaussian model, the peak, the core widths and the log profile, the last over the
// steps at and above the resolution only (kResolvedProfileStep). A thin wall
// passes light straight through whatever the normals' tilt (lobe.h "Transmission"), so every
// transmission lobe is centred on the same direction, ⟨T_a, T_b⟩ = trans_inner(α²_T,a, α²_T,b) (α²_T
// the core's width 1/P), the Gaussian model of spec_inner at tan²θ = 0, and each is at its own peak,
// π·D = P, at the straight-through pairs wi = −wo (the mirrored half vector is then the lobe's normal).
inline double trans_inner(double alpha2_a, double alpha2_b) { return spec_inner(alpha2_a, alpha2_b, 0.0); }
inline bool has_transmission(const Summary& s) { return s.trans != glm::dvec3(0.0); }
// Σ_ij (trans_i·trans_j/3)·⟨T_i, T_j⟩: the squared L2 norm of the union's transmission; 0 where no
// member transmits.
double union_trans_norm2(std::span<const Member> u);

// Horizons: the linear part of the cosine factors is kept exactly, but where the lobes' horizons
// differ (a lune of width δ, the angle between the normals) the merged lobe's smooth horizon differs
// from theirs; diffuse and grazing specular (Fresnel rises toward 1) both feel it. Plus the coupling
// of color and normal (ρ̄·n̄ ≠ E[ρ·n]). The pairs' sums do not depend on the merged lobe, so a union's
// are made once for its bound and its cost: horizon = 0.4·H²·lune + coupling, where H is the merged
// lobe's amplitude at the horizon (its ρ and F0).
struct HorizonSums {
  double lune = 0;      // Σ w_a·w_b/W · δ_ab
  double coupling = 0;  // Σ (4/3)·(w_a·w_b/W)²·Δρ²·2(1 − cos δ_ab)
  double cost(double rho, double f0) const {
    const double amp = rho + f0 + 0.2 * (1.0 - f0);
    return 0.4 * amp * amp * lune + coupling;
  }
};

// A diffuse transmission (diffuse_transmission.h) adds no term: its shape is fixed and a merge keeps its
// flux, so its union's error is these horizons' with τd for ρ, which changed the transmitted e_log of
// the layer's measured materials by 10⁻⁴ (docs/mip-algorithm.md §4.7).

// W: the union's weight.
HorizonSums horizon_sums(std::span<const Member> u, double W);

// The union's weight, Σ w.
double union_weight(std::span<const Member> u);

// A lower bound of union_cost that needs no merge: its horizon term alone (every other term is ≥ 0),
// with the merged ρ and F0 taken as the weighted means merge_base makes (less a relative 1e-6 for the
// float rounding of the merged lobe's).
double union_cost_bound(std::span<const Member> u, const HorizonSums& h);

// What union_cost needs of the union alone: its specular and transmission norm² (union_spec_norm2,
// union_trans_norm2) and horizon sums.
struct UnionTerms {
  double self = 0;
  HorizonSums horizon;
  double trans_self = 0;
};

UnionTerms union_terms(std::span<const Member> u);

// The estimated squared error of replacing the union u by the lobe m, whose union has the terms `t`
// (union_terms): the specular L2 error of the Gaussian model, the horizons, the highlight about the
// geometric normal, the core widths and the log profile, each below, and the transmission's L2 error
// where the union transmits. For two lobes these are the terms of the pair; for more, the pair terms
// summed over the pairs (horizons) or the union's sums in place of the pair's.
double union_cost(std::span<const Member> u, const UnionTerms& t, const Summary& m, bool by_amp, double peak_weight);


// For unions of rough lobes only (α² at or above the resolution, where shapes are smooth and no peak
// needs keeping): a cheap stand-in for union_cost that orders the merges down to max_lobes the same
// way on the presets (bench/results/mip.md) at a tenth of the cost — Ward's criterion (Ward 1963,
// "Hierarchical Grouping to Optimize an Objective Function": the product of the weights over their
// sum) times the squared distance of the shapes (log-roughness, the normals' offset relative to the
// lobes' widths) scaled by the specular amplitude's L2 norm, plus the horizon term of union_cost; and
// where they transmit, the transmission's (merge_cost.cpp, trans_distance).
double rough_distance(const Summary& a, const Summary& b);

}  // namespace svbrdf::reduction
