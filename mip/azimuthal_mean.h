#pragma once
// The mean over azimuth, about the geometric normal z, of one lobe's microfacet distribution D at a
// polar angle θ of the half vector: ⟨D⟩(θ) = (1/2π) ∫ D(h(θ, φ)) dφ. It is the radial profile of the
// lobe about z, which a coarse texel's radial correction compares (radial_correction.h).
//
// Every D of lobe.h depends on h only through c = n̂·h, and for h at (θ, φ) about z and n̂ tilted by δ,
// c = A + B cos φ with A = cos θ cos δ, B = sin θ sin δ. GGX, D = α²/(π(1 − k c²)²) with k = 1 − α²
// (Walter et al. 2007, eq. 33), splits by partial fractions in c into terms 1/(1 ∓ √k c)^m whose
// azimuthal means are closed form:
//   ⟨1/(p + q cos φ)⟩ = (p² − q²)^(−1/2),   ⟨1/(p + q cos φ)²⟩ = p (p² − q²)^(−3/2)   (p > |q|),
// and a roughness mixture's band, L/(π(1 − k_l c²)(1 − k_h c²)), splits into two such first-power
// terms. The Beckmann share of a spread core has no closed form: the midpoint rule on the arc of φ
// where lobe_d does not cut it (tan²/b² < 60). Where the circle reaches the lobe's horizon (c ≤ 0 for
// some φ) or α² ≥ 1 (no real factors), the trapezoid rule over φ.
#include <array>

#include "mip/lobe.h"

namespace svbrdf {

double azimuthal_mean_d(const LobeShape<double>& shape, double theta);
// The Fourier coefficients of D over the azimuth ψ measured from the lobe's tilt, ⟨D cos nψ⟩ for
// n = 0, 1, 2 (D is even in ψ, so its sine coefficients vanish; n = 0 is ⟨D⟩), at once: they share
// their roots. The same closed forms: the coefficients of 1/(p + q cos ψ) are ρⁿ/√(p² − q²) with
// ρ = (√(p² − q²) − p)/q, and those of its square −∂/∂p of them.
std::array<double, 3> azimuthal_fourier_d(const LobeShape<double>& shape, double theta);

}  // namespace svbrdf
