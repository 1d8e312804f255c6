#pragma once
// KHR_materials_iridescence: the Fresnel reflectance of a base covered by a thin dielectric film,
// Belcour & Barla 2017, "A Practical Extension to Microfacet Theory for the Modeling of Varying
// Iridescence" (ACM TOG 36(4)), in the approximate form of the extension's implementation notes:
// Schlick reflectances at both interfaces, phase shifts of 0 or π, the Airy series summed to its
// second harmonic, and the spectral integration in closed form (the Fourier transform of a Gaussian
// fit of the CIE XYZ sensitivities), then XYZ → linear Rec.709.
#include <glm/glm.hpp>

#include "appearance/bsdf.h"

namespace svbrdf {

// Below this film thickness (nm) the result fades (smoothstep) to the plain Schlick Fresnel of the
// base, F0 + (1 − F0)(1 − cos)^5, the term the extension uses without iridescence, so that thickness
// 0 is no film at all. The closed form does not reach it by itself: its Schlick first interface
// still reflects at grazing when the film ior equals the outside's, and at thickness → 0 it
// differs from the no-film Fresnel by up to 0.4 (film ior 2.3, grazing), a visible seam where a
// thickness texture reaches 0. 30 nm lies below the first interference minimum of every visible
// wavelength for film iors up to 3 (λ/(4n) ≥ 380/12 ≈ 32 nm) and below the extension's default
// thickness range, 100–400 nm.
inline constexpr float kIridescenceFadeThickness = 30.0f;

// The base's ior from its normal-incidence reflectance against air (the extension's Fresnel0ToIor):
// n = (1 + √F0) / (1 − √F0), per channel. F0 is clamped to 0.9999 so n stays finite. Used for both
// dielectric and metallic bases; a metal's extinction is taken as 0 (the extension does the same,
// as κ cannot be recovered from F0).
Rgb iridescence_base_ior(const Rgb& base_f0);

// F_iridescence, the RGB reflectance in [0, 1] of outside | film | base at the interface cosine
// cos_theta1 = wo·h (> 0; the cosine on the outside), for
//   thickness_nm  film thickness in nanometres (the extension's iridescenceThickness, ≥ 0),
//   film_ior      iridescenceIor (default 1.3),
//   base_f0       the base's F0: for the dielectric base its F0 from ior and KHR_materials_specular,
//                 for the metal base the base color (the extension converts both alike),
//   outside_ior   1 in air; the clearcoat's ior when a clearcoat lies above.
// When light cannot enter the film (film_ior < outside_ior beyond the critical angle) it is 1.
// The extension mixes it with the plain Schlick term: F = mix(F_schlick, F_iridescence,
// iridescenceFactor).
Rgb iridescence_fresnel(float cos_theta1, float thickness_nm, float film_ior, const Rgb& base_f0,
                        float outside_ior = 1.0f);

}  // namespace svbrdf
