#pragma once
// A lobe (lobe.h) as the MIP file stores it (mip_file.h), 26 bytes: its weight, ρ, F0, α, shape and
// skirt as half floats and its normal as stored_normal.h codes it. The BRDF pyramid's build rounds
// every lobe to this (round_to_stored), which is what makes the file's round trip bit-identical and
// what its figures measure; the MIP file reads and writes the codes. A user of the pyramid needs none
// of this.
#include <cstdint>

#include "mip/lobe.h"

namespace svbrdf {

// A lobe's shape (lobe.h) in two numbers, the MIP file's shape and skirt channels, as half floats.
// The shape code: ln(alpha2_hi/alpha2) > 0 for a roughness mixture whose upper part is the band,
// −(1 + ln(alpha2_hi/alpha2)) < −1 for one whose upper part is an atom (a two-point mixture), −μ ∈ [−1, 0]
// for a spread core with GGX share μ (−1: plain GGX): 5e-4 relative on μ and on the mixture's span,
// which moves its tail and peak moments by less than that. Mixtures spanning less than 0.1 % of α²
// store as plain GGX (lobe_shape treats them so below 0.01 %). set_lobe_shape_code sets alpha2_hi, the
// mixture's kind (skirt 1 or 0) or the core's μ (ggx).
float lobe_shape_code(const Lobe& lobe);
void set_lobe_shape_code(Lobe& lobe, float code);
// The skirt code: a spread core's c ≥ 1; a roughness mixture's upper share β, two-sided — β itself up
// to ½, β − 1 ∈ (−½, 0] above — so that a half keeps 5e-4 relative on the smaller of β and 1 − β (both
// shares carry moments: the atom the peak, the upper part the tail); 1 for plain GGX.
// set_lobe_skirt_code needs the lobe's shape code set first (it tells a mixture from a core).
float lobe_skirt_code(const Lobe& lobe);
void set_lobe_skirt_code(Lobe& lobe, float code);

// A lobe's stretch (lobe.h, "Stretched shapes") as the file stores it: ln r as a half (5e-4 relative),
// and the direction's angle φ in [0, π) (a stretch is axial) in steps of π/2^20 (3e-6 rad, so that a
// stretch of r = 1000 turns its wide axis into the narrow one by 0.3 % of the narrow width) as an
// integer channel. Stretches of ln r < kLeastStoredLnStretch (r < 1.001, a 0.05 % change of the slopes'
// widths) store as none (code 0), which also keeps the code's round trip exact: ln of the float
// e^code lies within 6e-8 of the code, and a half's spacing there is ≥ 9.5e-7.
inline constexpr double kLeastStoredLnStretch = 1e-3;
inline constexpr int kStretchDirectionBits = 20;
float stretch_code(float stretch);
std::uint32_t stretch_direction_code(const glm::vec2& direction);
void set_stretch_code(float& stretch, glm::vec2& direction, float code, std::uint32_t direction_code);
inline float lobe_stretch_code(const Lobe& lobe) { return stretch_code(lobe.stretch); }
inline std::uint32_t lobe_stretch_direction_code(const Lobe& lobe) { return stretch_direction_code(lobe.stretch_dir); }
inline void set_lobe_stretch_code(Lobe& lobe, float code, std::uint32_t direction) {
  set_stretch_code(lobe.stretch, lobe.stretch_dir, code, direction);
}
// The same of the transmission's own stretch (lobe.h "Transmission").
inline float lobe_transmission_stretch_code(const Lobe& lobe) { return stretch_code(lobe.transmission_stretch); }
inline std::uint32_t lobe_transmission_stretch_direction_code(const Lobe& lobe) {
  return stretch_direction_code(lobe.transmission_stretch_dir);
}
inline void set_lobe_transmission_stretch_code(Lobe& lobe, float code, std::uint32_t direction) {
  set_stretch_code(lobe.transmission_stretch, lobe.transmission_stretch_dir, code, direction);
}

// Rounds a lobe to what the MIP file stores: weight, colors (f0_tint, the transmission's τ and τ90 and the
// diffuse transmission's τd and τd90 among them), its coat and sheen shares, α and the transmission's α_T and α_T,hi (the square roots of alpha2,
// transmission_alpha2 and transmission_alpha2_hi), shape code and skirt as half floats, the normal as
// stored_normal.h codes it, its stretch and its transmission's stretch as above.
void round_to_stored(Lobe& lobe);

// The same for a coat lobe (coat_layer.h), whose colours the file does not store: F0 = 0.04 and F90 = 1
// as the extension fixes them, no diffuse term.
void round_coat_lobe_to_stored(Lobe& lobe);
// Gives a coat lobe the colours the extension fixes (F0 0.04, F90 1, no diffuse, no tint, no coat of its
// own), what the file does not store of it.
void set_coat_colours(Lobe& lobe);

// Bytes a stored lobe takes: the normal's direction as a 32-bit code (stored_normal.h); weight, ρ (3),
// F0 (3), the normal's length deficit, α, the shape code and the skirt as half floats.
inline constexpr int kBytesPerLobe = 4 + 11 * 2;
// What the specular layer adds to a stored lobe (ρ90 and F90 as four halves; mip_file.h).
inline constexpr int kBytesPerSpecularLayer = 4 * 2;
// What the tint layer adds to a stored lobe (f0_tint as three halves), in pyramids built for tinted
// lookups (brdf_pyramid.h BrdfBuildOptions::tint).
inline constexpr int kBytesPerTintLayer = 3 * 2;
// What the anisotropy adds to a stored lobe (its stretch: ln r as a half, the direction's code as a
// 32-bit integer), in levels where some lobe is stretched.
inline constexpr int kBytesPerStretch = 2 + 4;
// What a thin-walled transmission adds to a stored lobe (τ as three halves, α_T and α_T,hi as one each;
// lobe.h "Transmission"), in levels where some lobe transmits, and τ90 (three halves) in levels where
// some lobe's is not 0 (a transmitting material whose specular layer is not plain).
inline constexpr int kBytesPerTransmission = 5 * 2;
inline constexpr int kBytesPerTransmission90 = 3 * 2;
// The transmission's own stretch, as kBytesPerStretch, in levels where some lobe's transmission is
// stretched.
inline constexpr int kBytesPerTransmissionStretch = kBytesPerStretch;
// What a diffuse transmission adds to a stored lobe (diffuse_transmission.h): τd as three halves, in
// levels where some lobe transmits diffusely, and τd90 as three halves, in levels where some lobe's is
// not 0 (a diffusely transmitting material whose specular layer is not plain).
inline constexpr int kBytesPerDiffuseTransmission = 3 * 2;
inline constexpr int kBytesPerDiffuseTransmission90 = 3 * 2;

}  // namespace svbrdf
