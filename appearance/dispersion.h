#pragma once
// KHR_materials_dispersion: the index of refraction as a function of wavelength, from the material's
// ior (n_d, at 587.6 nm) and its dispersion = 20/V_d (V_d the Abbe number), by the extension's
// two-term Cauchy equation n(λ) = max(n_d + (n_d − 1)/V_d·(523655/λ² − 1.5168), 1), λ in nm, whose
// coefficients make n(486.1) − n(656.3) = (n_d − 1)/V_d.
//
// The renderer works in RGB, so each channel refracts with the index at one wavelength: the
// dominant wavelength of its Rec.709 primary (the spectral locus point on the line from the D65
// white through the primary's chromaticity): 611.3 nm (red), 549.1 nm (green), 464.3 nm (blue).
// A path that refracts through a dispersive surface follows one channel from there on (render/
// integrator.cpp), as a spectral renderer follows one wavelength.
namespace svbrdf {

inline constexpr float kChannelWavelengthNm[3] = {611.3f, 549.1f, 464.3f};

// n(λ) for a material of index ior (n_d) and dispersion 20/V_d; ior itself where dispersion is 0.
inline float dispersion_ior(float ior, float dispersion, float wavelength_nm) {
  if (!(dispersion > 0.0f)) return ior;
  const float n = ior + (ior - 1.0f) * (dispersion / 20.0f) * (523655.0f / (wavelength_nm * wavelength_nm) - 1.5168f);
  return n > 1.0f ? n : 1.0f;
}

}  // namespace svbrdf
